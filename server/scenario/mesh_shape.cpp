// Shape::mesh: the solid of a closed triangle mesh as exact convex cells (geometry.h).
//
// The plan (x, y) is split, binary-space-partition fashion, along the supporting lines of the
// triangles' projected edges until no edge crosses the interior of a piece. Over such a piece each
// non-vertical triangle either covers all of it or none, and triangles of a surface that does not
// cross itself keep their order in z across it; walking up through them, the solid lies between
// each downward-facing triangle and the upward-facing one above it. Each such stretch is a convex
// cell: the piece's vertical planes, the lower triangle's plane and the upper one's. A split line
// gives its two sides the same plane with opposite signs, so a point on it lies in one side's cell
// or the other's, never in neither.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "server/scenario/case_error.h"
#include "server/scenario/geometry.h"
#include "server/scenario/number_text.h"

namespace cascade {
namespace {

using Vec2 = Eigen::Vector2d;

// The half-plane normal·x <= offset of the plan.
struct Line {
  Vec2 normal;
  double offset;
  double signed_distance(const Vec2& x) const { return normal.dot(x) - offset; }
};

// A convex piece of the plan: its vertices (counter-clockwise), the half-planes that bound it and
// the triangles whose projections may overlap it.
struct Piece {
  std::vector<Vec2> vertices;
  std::vector<Line> lines;
  std::vector<int> triangles;
};

std::vector<Vec2> clip(const std::vector<Vec2>& v, const Line& line) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 &a = v[i], &b = v[(i + 1) % v.size()];
    const double sa = line.signed_distance(a), sb = line.signed_distance(b);
    if (sa <= 0.0) out.push_back(a);
    if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) out.push_back(a + (sa / (sa - sb)) * (b - a));
  }
  return out;
}

double area(const std::vector<Vec2>& v) {
  double a = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 &p = v[i], &q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

double perimeter(const std::vector<Vec2>& v) {
  double p = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) p += (v[(i + 1) % v.size()] - v[i]).norm();
  return p;
}

Vec2 centroid(const std::vector<Vec2>& v) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& p : v) c += p;
  return c / double(v.size());
}

struct Triangle {
  Vec3 p[3];
  Vec3 normal;        // outward unit normal
  double offset = 0;  // normal · p[0]
  Vec2 plan[3];       // the projection, counter-clockwise
  bool vertical = false;
  double z_at(const Vec2& x) const { return (offset - normal.x() * x.x() - normal.y() * x.y()) / normal.z(); }
};

// Whether the segment a–b passes through the interior of the piece (not only along its edge).
bool crosses(const Piece& piece, const Vec2& a, const Vec2& b, double eps) {
  double t0 = 0.0, t1 = 1.0;  // Liang–Barsky against the piece's half-planes
  const Vec2 d = b - a;
  for (const Line& l : piece.lines) {
    const double sa = l.signed_distance(a), rate = l.normal.dot(d);
    if (std::abs(rate) < 1e-300) {
      if (sa > -eps) return false;  // parallel, on or beyond the line
      continue;
    }
    const double t = -sa / rate;
    if (rate > 0.0) t1 = std::min(t1, t);
    else t0 = std::max(t0, t);
    if (t1 <= t0) return false;
  }
  if ((t1 - t0) * d.norm() <= eps) return false;
  const Vec2 mid = a + 0.5 * (t0 + t1) * d;
  for (const Line& l : piece.lines)
    if (l.signed_distance(mid) > -eps) return false;  // along the piece's boundary
  return true;
}

// Whether a triangle's projection may overlap the piece's interior: no separating axis among the
// piece's lines and the triangle's edges. Keeping one too many costs time, not correctness.
bool overlaps(const Piece& piece, const Triangle& t, double eps) {
  for (const Line& l : piece.lines) {
    bool outside = true;
    for (const Vec2& p : t.plan) outside = outside && l.signed_distance(p) >= -eps;
    if (outside) return false;
  }
  for (int k = 0; k < 3; ++k) {
    const Vec2 e = t.plan[(k + 1) % 3] - t.plan[k];
    const Vec2 n(e.y(), -e.x());  // outward for a counter-clockwise triangle
    bool outside = true;
    for (const Vec2& p : piece.vertices) outside = outside && n.dot(p - t.plan[k]) >= -eps * e.norm();
    if (outside) return false;
  }
  return true;
}

bool covers(const Triangle& t, const Vec2& x) {
  for (int k = 0; k < 3; ++k) {
    const Vec2 e = t.plan[(k + 1) % 3] - t.plan[k];
    if (e.x() * (x - t.plan[k]).y() - e.y() * (x - t.plan[k]).x() < 0.0) return false;
  }
  return true;
}

Plane vertical(const Line& l) { return {Vec3(l.normal.x(), l.normal.y(), 0.0), l.offset}; }

// The column (along `axis`, 0 or 1) of an n × n plan grid over `bounds` that holds coordinate v:
// one formula for filing the cells and for looking a point up, so both round alike.
int grid_square(const Aabb& bounds, double v, int axis, int n) {
  return std::clamp(int((v - bounds.lo[axis]) / (bounds.hi[axis] - bounds.lo[axis]) * n), 0, n - 1);
}

}  // namespace

Shape Shape::mesh(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                  const std::string& key) {
  Shape s;
  s.kind_ = Kind::mesh;
  s.dimensions_ = 3;
  for (const Vec3& v : vertices) s.bounds_.extend(v);
  const double size = (s.bounds_.hi - s.bounds_.lo).norm();
  const double eps = 1e-9 * size;

  std::vector<Triangle> tri;
  for (const auto& t : triangles) {
    Triangle m;
    for (int k = 0; k < 3; ++k) m.p[k] = vertices[t[k]];
    const Vec3 n = (m.p[1] - m.p[0]).cross(m.p[2] - m.p[0]);
    m.normal = n.normalized();
    m.offset = m.normal.dot(m.p[0]);
    s.faces_.push_back(Face::make({m.p[0], m.p[1], m.p[2]}, m.normal));
    // Near-vertical triangles cover no area of the plan; their neighbours' edges bound the columns.
    m.vertical = std::abs(n.z()) <= 1e-12 * n.norm();
    for (int k = 0; k < 3; ++k) m.plan[k] = m.p[k].head<2>();
    if (n.z() < 0.0) std::swap(m.plan[1], m.plan[2]);
    tri.push_back(m);
  }

  // The plan's partition, depth first; each piece starts with every triangle that may overlap it.
  Piece root;
  root.vertices = {s.bounds_.lo.head<2>(), Vec2(s.bounds_.hi.x(), s.bounds_.lo.y()), s.bounds_.hi.head<2>(),
                   Vec2(s.bounds_.lo.x(), s.bounds_.hi.y())};
  root.lines = {{Vec2(1, 0), s.bounds_.hi.x()}, {Vec2(-1, 0), -s.bounds_.lo.x()},
                {Vec2(0, 1), s.bounds_.hi.y()}, {Vec2(0, -1), -s.bounds_.lo.y()}};
  for (int t = 0; t < int(tri.size()); ++t)
    if (!tri[t].vertical) root.triangles.push_back(t);
  std::vector<Piece> stack{std::move(root)};
  while (!stack.empty()) {
    Piece piece = std::move(stack.back());
    stack.pop_back();
    std::optional<Line> split;
    for (int t : piece.triangles) {
      for (int k = 0; k < 3 && !split; ++k) {
        const Vec2 &a = tri[t].plan[k], &b = tri[t].plan[(k + 1) % 3];
        if (crosses(piece, a, b, eps)) {
          const Vec2 d = (b - a).normalized();
          const Vec2 n(d.y(), -d.x());
          split = Line{n, n.dot(a)};
        }
      }
      if (split) break;
    }
    if (split) {
      for (const Line& side : {*split, Line{-split->normal, -split->offset}}) {
        Piece child;
        child.vertices = clip(piece.vertices, side);
        // Even a sliver is kept: dropping one left a hole 3·10⁻⁸ m wide where three edge lines
        // (float32 vertices of an STL file) nearly met, and the floor under it kept a wetted piece.
        if (child.vertices.size() < 3 || !(area(child.vertices) > 0.0)) continue;
        child.lines = piece.lines;
        child.lines.push_back(side);
        for (int t : piece.triangles)
          if (overlaps(child, tri[t], eps)) child.triangles.push_back(t);
        stack.push_back(std::move(child));
      }
      continue;
    }

    // A final piece: the triangles over it in z order, and the solid between down- and up-facing.
    const Vec2 c = centroid(piece.vertices);
    std::vector<std::pair<double, int>> column;
    for (int t : piece.triangles)
      if (covers(tri[t], c)) column.emplace_back(tri[t].z_at(c), t);
    std::sort(column.begin(), column.end());
    // Over the piece the triangles must keep their centre's order: the gap between two in turn is
    // linear over the piece, so a crossing anywhere in it shows at one of its vertices.
    for (std::size_t k = 0; k + 1 < column.size(); ++k) {
      const Triangle &below = tri[column[k].second], &above = tri[column[k + 1].second];
      const double slopes = below.normal.head<2>().norm() / std::abs(below.normal.z()) +
                            above.normal.head<2>().norm() / std::abs(above.normal.z());
      for (const Vec2& v : piece.vertices)
        if (above.z_at(v) < below.z_at(v) - eps * (1.0 + slopes))
          throw CaseError(key, "the mesh's surface crosses itself above map point (" + number_text(v.x()) + ", " +
                                   number_text(v.y()) + ")");
    }
    ConvexCell sides;
    for (const Line& l : piece.lines) {  // only the lines the piece touches: the others cut nothing
      bool touches = false;
      for (const Vec2& p : piece.vertices) touches = touches || l.signed_distance(p) > -eps;
      if (touches) sides.planes.push_back(vertical(l));
    }
    Aabb plan;
    for (const Vec2& p : piece.vertices) plan.extend(Vec3(p.x(), p.y(), 0.0));
    for (std::size_t k = 0; k < column.size(); k += 2) {
      const Triangle& low = tri[column[k].second];
      if (k + 1 == column.size() || low.normal.z() > 0.0 || tri[column[k + 1].second].normal.z() < 0.0) {
        // A sliver thinner than eps, whose centre rounding may put on either side of an edge: no
        // cell, a gap far below the builder's tolerance.
        if (2.0 * std::abs(area(piece.vertices)) <= eps * perimeter(piece.vertices)) break;
        throw CaseError(key, "the mesh's surface crosses itself or is not closed above map point (" +
                                 number_text(c.x()) + ", " + number_text(c.y()) + ")");
      }
      const Triangle& high = tri[column[k + 1].second];
      if (column[k + 1].first - column[k].first <= eps) continue;  // two parts touching
      ConvexCell cell = sides;
      cell.planes.push_back({low.normal, low.offset});
      cell.planes.push_back({high.normal, high.offset});
      Aabb b = plan;
      b.lo.z() = std::min({low.p[0].z(), low.p[1].z(), low.p[2].z()});
      b.hi.z() = std::max({high.p[0].z(), high.p[1].z(), high.p[2].z()});
      s.cells_.push_back(std::move(cell));
      s.cell_bounds_.push_back(b.expanded(eps));  // the vertices were clipped, the planes are exact
    }
  }

  // The plan grid of contains(): about one cell per square.
  const int n = std::max(1, int(std::sqrt(double(s.cells_.size()))));
  s.index_n_ = n;
  s.index_.assign(std::size_t(n) * n, {});
  for (int c = 0; c < int(s.cells_.size()); ++c) {
    const Aabb& b = s.cell_bounds_[c];
    for (int j = grid_square(s.bounds_, b.lo.y(), 1, n); j <= grid_square(s.bounds_, b.hi.y(), 1, n); ++j)
      for (int i = grid_square(s.bounds_, b.lo.x(), 0, n); i <= grid_square(s.bounds_, b.hi.x(), 0, n); ++i)
        s.index_[std::size_t(j) * n + i].push_back(c);
  }
  return s;
}

bool Shape::mesh_contains(const Vec3& x) const {
  if (bounds_.squared_distance(x) > 0.0) return false;
  const int i = grid_square(bounds_, x.x(), 0, index_n_), j = grid_square(bounds_, x.y(), 1, index_n_);
  for (int c : index_[std::size_t(j) * index_n_ + i])
    if (cell_bounds_[c].squared_distance(x) == 0.0 && cells_[c].contains(x)) return true;
  return false;
}

}  // namespace cascade
