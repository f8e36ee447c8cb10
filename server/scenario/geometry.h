// Solid and fluid regions of a scenario: the shapes of scenario.proto, their planar surface pieces
// ("faces") with exact closest points, and the clipping of faces by other solids that the particle
// builder needs to find the wetted surface of the solid boundary (paper Section 3.3.1).
//
// All geometry is in 3D. A 2D case (x, z) is embedded as (x, 0, z): its shapes are prisms infinite
// along y, their faces are segments in the y = 0 plane and every normal has a zero y component.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace cascade::v1 {
class Shape;
class TerrainGrid;
}

namespace cascade {

using Vec3 = Eigen::Vector3d;

// Axis-aligned box; a side may be infinite (half-spaces).
struct Aabb {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());

  static Aabb everything() {
    const double inf = std::numeric_limits<double>::infinity();
    return {Vec3::Constant(-inf), Vec3::Constant(inf)};
  }
  bool empty() const { return (lo.array() > hi.array()).any(); }
  void extend(const Vec3& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  Aabb intersection(const Aabb& b) const { return {lo.cwiseMax(b.lo), hi.cwiseMin(b.hi)}; }
  Aabb expanded(double margin) const { return {lo.array() - margin, hi.array() + margin}; }
  // Squared distance from x to the box (0 inside).
  double squared_distance(const Vec3& x) const {
    const Vec3 d = (lo - x).cwiseMax(x - hi).cwiseMax(Vec3::Zero());
    return d.squaredNorm();
  }
};

// The closed half-space normal·x <= offset.
struct Plane {
  Vec3 normal;
  double offset = 0.0;
  double signed_distance(const Vec3& x) const { return normal.dot(x) - offset; }
};

// Convex polytope: the intersection of half-spaces (unbounded where the planes leave it open).
struct ConvexCell {
  std::vector<Plane> planes;
  bool contains(const Vec3& x) const {
    for (const Plane& p : planes)
      if (p.signed_distance(x) > 0.0) return false;
    return true;
  }
  ConvexCell translated(const Vec3& shift) const;
};

// A flat, convex piece of surface: a segment (2 vertices, 2D cases) or a convex polygon (>= 3
// coplanar vertices, counter-clockwise seen from the side the normal points to). The normal is a
// unit vector pointing out of the solid.
struct Face {
  std::vector<Vec3> vertices;
  Vec3 normal = Vec3::Zero();

  // Builds a face and orders polygon vertices counter-clockwise about `outward`.
  static Face make(std::vector<Vec3> vertices, const Vec3& outward);

  bool is_segment() const { return vertices.size() == 2; }
  Vec3 closest_point(const Vec3& x) const;
  double measure() const;  // length of a segment, area of a polygon
  Aabb bounds() const;
  Face flipped() const;
  Face translated(const Vec3& shift) const;
};

// One shape of scenario.proto. `contains` is exact (crossing test for polygons); `cells` is a
// decomposition into convex cells with disjoint interiors (polygons are triangulated) that face
// clipping uses; `faces` cover the whole surface with outward normals.
class Shape {
 public:
  enum class Kind { box, polygon, extruded_polygon, half_space, heightfield, mesh };

  // `min`, `max`, `point`, `normal` are `dimensions`-component vectors as in the schema: (x, z) in
  // 2D. `polygon` vertices are (x, z) pairs. Invalid input throws CaseError naming `key`.
  static Shape box(const std::vector<double>& min, const std::vector<double>& max, int dimensions,
                   const std::string& key);
  static Shape polygon(const std::vector<Eigen::Vector2d>& vertices, const std::string& key);
  static Shape extruded_polygon(const std::vector<Eigen::Vector2d>& vertices, double y_min, double y_max,
                                const std::string& key);
  // A half-space's surface is an infinite plane; its face is the plane clipped to `face_bounds`
  // (a box well beyond the domain), so closest points inside the domain are exact.
  static Shape half_space(const std::vector<double>& point, const std::vector<double>& normal, int dimensions,
                          const Aabb& face_bounds, const std::string& key);

  // The solid between two height fields over the rectangle x.front()..x.back() (3D: and
  // y.front()..y.back(); 2D: y = {0}): heights at the nodes (x[i], y[j]), x fastest, linear between
  // them (on the two triangles of each node cell, split along the diagonal from (i, j) to
  // (i + 1, j + 1), in 3D), lower <= upper everywhere. A terrain layer (server/terrain).
  static Shape heightfield(std::vector<double> x, std::vector<double> y, std::vector<double> lower,
                           std::vector<double> upper, int dimensions, const std::string& key);

  // The solid bounded by a closed triangle mesh (3D; mesh_shape.cpp), triangles counter-clockwise
  // seen from outside, already checked to be closed and consistently oriented (stl_solid.h). Its
  // cells are vertical columns: the plan is split along the triangles' projected edges until no
  // edge crosses a piece, and each piece is cut in z between the triangles above it, so every cell
  // is exact (bounded by the mesh's own planes). A surface that crosses itself throws CaseError.
  static Shape mesh(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                    const std::string& key);

  Kind kind() const { return kind_; }
  int dimensions() const { return dimensions_; }
  bool contains(const Vec3& x) const;
  const std::vector<Face>& faces() const { return faces_; }
  const std::vector<ConvexCell>& cells() const { return cells_; }
  const Aabb& bounds() const { return bounds_; }  // infinite along y in 2D
  Shape translated(const Vec3& shift) const;

 private:
  Kind kind_ = Kind::box;
  int dimensions_ = 3;
  std::vector<Eigen::Vector2d> outline_;  // polygon vertices in (x, z), for the crossing test
  double y_min_ = 0.0, y_max_ = 0.0;      // extruded polygon
  std::vector<double> node_x_, node_y_, lower_, upper_;  // heightfield
  double height(const std::vector<double>& field, double x, double y) const;
  // mesh: each cell's bounds and a uniform plan grid over bounds_ listing the cells that reach
  // into each of its index_n_ × index_n_ squares, so that contains() tests a few cells.
  std::vector<Aabb> cell_bounds_;
  int index_n_ = 0;
  std::vector<std::vector<int>> index_;
  bool mesh_contains(const Vec3& x) const;
  std::vector<ConvexCell> cells_;
  std::vector<Face> faces_;
  Aabb bounds_;
};

// Shape from its schema message (`key` names the message, e.g. `bodies[2].shape`). A terrain
// layer takes the spec's terrain grid (`terrain`) and lattice spacing `dp`; a bedrock reaches down
// to half_space_face_bounds' bottom.
Shape shape_from_spec(const v1::Shape& spec, int dimensions, const Aabb& half_space_face_bounds,
                      const v1::TerrainGrid& terrain, double dp, const std::string& key);

// A shape minus subtracted shapes (Body.shape minus Body.subtract).
class Region {
 public:
  Region(Shape shape, std::vector<Shape> subtract) : shape_(std::move(shape)), subtract_(std::move(subtract)) {}

  bool contains(const Vec3& x) const;
  const Shape& shape() const { return shape_; }
  const std::vector<Shape>& subtracted() const { return subtract_; }
  const Aabb& bounds() const { return shape_.bounds(); }
  Region translated(const Vec3& shift) const;

  // The region's surface as convex pieces with normals pointing out of the region: the parts of
  // the shape's faces not inside a subtracted shape, and the parts of the subtracted shapes' faces
  // inside the shape (flipped, pointing into the subtracted space). A piece is kept where points
  // `gap` away from it on the region's side are in the region, and on the other side are not.
  std::vector<Face> surface(double gap) const;

 private:
  Shape shape_;
  std::vector<Shape> subtract_;
};

// Face clipping on convex pieces. A piece thinner than `tolerance` is dropped.
std::vector<Face> clip_to_cell(const Face& face, const ConvexCell& cell, double tolerance);   // face ∩ cell
std::vector<Face> cut_by_cell(const Face& face, const ConvexCell& cell, double tolerance);    // face \ cell
std::vector<Face> clip_to_cells(const std::vector<Face>& faces, const std::vector<ConvexCell>& cells,
                                double tolerance);  // faces ∩ (∪ cells), cells with disjoint interiors
std::vector<Face> cut_by_cells(const std::vector<Face>& faces, const std::vector<ConvexCell>& cells,
                               double tolerance);   // faces \ (∪ cells)
std::vector<Face> cut_by_region(const std::vector<Face>& faces, const Region& region,
                                double tolerance);  // faces \ region

}  // namespace cascade
