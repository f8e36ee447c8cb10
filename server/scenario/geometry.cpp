#include "server/scenario/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/terrain/terrain_grid.h"

namespace cascade {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// (x, z) in the case's coordinates → the 3D embedding; (x, y, z) unchanged.
Vec3 embed(const std::vector<double>& v, int dimensions) {
  return dimensions == 2 ? Vec3(v[0], 0.0, v[1]) : Vec3(v[0], v[1], v[2]);
}

void check_vector(const std::vector<double>& v, int dimensions, const std::string& key) {
  if (static_cast<int>(v.size()) != dimensions)
    throw CaseError(key, "needs " + std::to_string(dimensions) + " components, has " + std::to_string(v.size()));
  for (double c : v)
    if (!std::isfinite(c)) throw CaseError(key, "components must be finite numbers");
}

Vec3 closest_on_segment(const Vec3& a, const Vec3& b, const Vec3& x) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 == 0.0) return a;
  const double t = std::clamp((x - a).dot(d) / len2, 0.0, 1.0);
  return a + t * d;
}

// Twice the signed area of a polygon in the (x, z) plane; > 0 for counter-clockwise.
double twice_signed_area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0.0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % n];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return a;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Ear-clipping triangulation of a simple counter-clockwise polygon; triangles counter-clockwise.
std::vector<std::array<Eigen::Vector2d, 3>> triangulate(const std::vector<Eigen::Vector2d>& polygon,
                                                        const std::string& key) {
  std::vector<Eigen::Vector2d> p = polygon;
  std::vector<std::array<Eigen::Vector2d, 3>> triangles;
  double scale = 0.0;
  for (const auto& v : p) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  const double eps = 1e-12 * std::max(scale, 1e-300) * std::max(scale, 1e-300);
  while (p.size() > 3) {
    const std::size_t n = p.size();
    bool clipped = false;
    for (std::size_t i = 0; i < n && !clipped; ++i) {
      const auto& a = p[(i + n - 1) % n];
      const auto& b = p[i];
      const auto& c = p[(i + 1) % n];
      const double turn = cross2(a, b, c);
      if (std::abs(turn) <= eps) {  // collinear vertex: drop it, the outline is unchanged
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
        clipped = true;
        break;
      }
      if (turn < 0.0) continue;  // reflex vertex
      bool ear = true;
      for (std::size_t j = 0; j < n && ear; ++j) {
        if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
        const auto& q = p[j];
        if (cross2(a, b, q) >= -eps && cross2(b, c, q) >= -eps && cross2(c, a, q) >= -eps) ear = false;
      }
      if (!ear) continue;
      triangles.push_back({a, b, c});
      p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) throw CaseError(key, "polygon is self-intersecting or degenerate");
  }
  if (p.size() == 3 && cross2(p[0], p[1], p[2]) > eps) triangles.push_back({p[0], p[1], p[2]});
  return triangles;
}

// Outward plane of the edge a → b of a counter-clockwise outline in (x, z).
Plane edge_plane(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  Vec3 n(d.y(), 0.0, -d.x());
  n.normalize();
  return {n, n.dot(Vec3(a.x(), 0.0, a.y()))};
}

bool crossing_test(const std::vector<Eigen::Vector2d>& p, double x, double z) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y() > z) != (p[j].y() > z)) {
      const double xc = p[i].x() + (z - p[i].y()) * (p[j].x() - p[i].x()) / (p[j].y() - p[i].y());
      if (x < xc) inside = !inside;
    }
  }
  return inside;
}

std::vector<ConvexCell> box_cells(const Vec3& lo, const Vec3& hi, int dimensions) {
  ConvexCell c;
  for (int axis = 0; axis < 3; ++axis) {
    if (dimensions == 2 && axis == 1) continue;
    c.planes.push_back({Vec3::Unit(axis), hi[axis]});
    c.planes.push_back({-Vec3::Unit(axis), -lo[axis]});
  }
  return {c};
}

// The keep-side (signed distance <= 0) of a face cut by a plane; empty when nothing is left.
std::vector<Vec3> clip_vertices(const std::vector<Vec3>& v, const Plane& plane) {
  std::vector<Vec3> out;
  if (v.size() == 2) {
    const double s0 = plane.signed_distance(v[0]), s1 = plane.signed_distance(v[1]);
    if (s0 > 0.0 && s1 > 0.0) return out;
    if (s0 <= 0.0 && s1 <= 0.0) return v;
    const Vec3 cut = v[0] + (s0 / (s0 - s1)) * (v[1] - v[0]);
    return s0 <= 0.0 ? std::vector<Vec3>{v[0], cut} : std::vector<Vec3>{cut, v[1]};
  }
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % n];
    const double sa = plane.signed_distance(a), sb = plane.signed_distance(b);
    if (sa <= 0.0) out.push_back(a);
    if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) out.push_back(a + (sa / (sa - sb)) * (b - a));
  }
  return out;
}

// Whether a clipped piece is thinner than `tolerance` (and so dropped). A polygon clipped down to
// two vertices (a face lying on a cutting plane leaves its edge) is no face: kept as a segment, it
// put dummy layers under a terrain's edge where a wall met the domain's bottom.
bool degenerate(const std::vector<Vec3>& v, double tolerance, bool polygon) {
  if (v.size() < 2 || (polygon && v.size() < 3)) return true;
  if (v.size() == 2) return (v[1] - v[0]).norm() < tolerance;
  double perimeter = 0.0;
  Vec3 twice_area = Vec3::Zero();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& b = v[(i + 1) % v.size()];
    perimeter += (b - v[i]).norm();
    twice_area += (v[i] - v[0]).cross(b - v[0]);
  }
  return perimeter == 0.0 || twice_area.norm() / perimeter < tolerance;  // ≈ the piece's width
}

Face with_vertices(const Face& f, std::vector<Vec3> v) {
  Face g;
  g.vertices = std::move(v);
  g.normal = f.normal;
  return g;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

ConvexCell ConvexCell::translated(const Vec3& shift) const {
  ConvexCell c = *this;
  for (Plane& p : c.planes) p.offset += p.normal.dot(shift);
  return c;
}

Face Face::make(std::vector<Vec3> vertices, const Vec3& outward) {
  Face f;
  f.normal = outward.normalized();
  if (vertices.size() >= 3) {
    Vec3 newell = Vec3::Zero();
    for (std::size_t i = 0; i < vertices.size(); ++i)
      newell += (vertices[i] - vertices[0]).cross(vertices[(i + 1) % vertices.size()] - vertices[0]);
    if (newell.dot(f.normal) < 0.0) std::reverse(vertices.begin(), vertices.end());
  }
  f.vertices = std::move(vertices);
  return f;
}

Vec3 Face::closest_point(const Vec3& x) const {
  if (is_segment()) return closest_on_segment(vertices[0], vertices[1], x);
  const Vec3 q = x - (x - vertices[0]).dot(normal) * normal;
  const std::size_t n = vertices.size();
  bool inside = true;
  for (std::size_t i = 0; i < n && inside; ++i)
    inside = (vertices[(i + 1) % n] - vertices[i]).cross(q - vertices[i]).dot(normal) >= 0.0;
  if (inside) return q;
  Vec3 best = vertices[0];
  double best_d2 = kInf;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c = closest_on_segment(vertices[i], vertices[(i + 1) % n], x);
    const double d2 = (c - x).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = c;
  }
  return best;
}

double Face::measure() const {
  if (is_segment()) return (vertices[1] - vertices[0]).norm();
  Vec3 twice_area = Vec3::Zero();
  for (std::size_t i = 0; i < vertices.size(); ++i)
    twice_area += (vertices[i] - vertices[0]).cross(vertices[(i + 1) % vertices.size()] - vertices[0]);
  return 0.5 * twice_area.norm();
}

Aabb Face::bounds() const {
  Aabb b;
  for (const Vec3& v : vertices) b.extend(v);
  return b;
}

Face Face::flipped() const {
  Face f = *this;
  f.normal = -normal;
  std::reverse(f.vertices.begin(), f.vertices.end());
  return f;
}

Face Face::translated(const Vec3& shift) const {
  Face f = *this;
  for (Vec3& v : f.vertices) v += shift;
  return f;
}

// ---------------------------------------------------------------------------------------------

Shape Shape::box(const std::vector<double>& min, const std::vector<double>& max, int dimensions,
                 const std::string& key) {
  check_vector(min, dimensions, key + ".min");
  check_vector(max, dimensions, key + ".max");
  for (int d = 0; d < dimensions; ++d)
    if (!(min[d] < max[d])) throw CaseError(key + ".max", "every component must exceed the one of min");
  Shape s;
  s.kind_ = Kind::box;
  s.dimensions_ = dimensions;
  const Vec3 lo = embed(min, dimensions), hi = embed(max, dimensions);
  s.cells_ = box_cells(lo, hi, dimensions);
  s.bounds_ = {lo, hi};
  if (dimensions == 2) {
    s.bounds_.lo.y() = -kInf, s.bounds_.hi.y() = kInf;
    const Vec3 c[4] = {{lo.x(), 0, lo.z()}, {hi.x(), 0, lo.z()}, {hi.x(), 0, hi.z()}, {lo.x(), 0, hi.z()}};
    s.faces_ = {Face::make({c[0], c[1]}, -Vec3::UnitZ()), Face::make({c[1], c[2]}, Vec3::UnitX()),
                Face::make({c[2], c[3]}, Vec3::UnitZ()), Face::make({c[3], c[0]}, -Vec3::UnitX())};
    return s;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      Vec3 corner = side ? hi : lo;
      std::vector<Vec3> quad(4, corner);
      quad[0][u] = lo[u], quad[0][v] = lo[v];
      quad[1][u] = hi[u], quad[1][v] = lo[v];
      quad[2][u] = hi[u], quad[2][v] = hi[v];
      quad[3][u] = lo[u], quad[3][v] = hi[v];
      s.faces_.push_back(Face::make(std::move(quad), (side ? 1.0 : -1.0) * Vec3::Unit(axis)));
    }
  }
  return s;
}

namespace {

std::vector<Eigen::Vector2d> checked_outline(const std::vector<Eigen::Vector2d>& vertices, const std::string& key) {
  if (vertices.size() < 3) throw CaseError(key, "a polygon needs at least 3 vertices");
  for (const auto& v : vertices)
    if (!v.allFinite()) throw CaseError(key, "vertex coordinates must be finite numbers");
  std::vector<Eigen::Vector2d> outline = vertices;
  const double area2 = twice_signed_area(outline);
  if (area2 == 0.0) throw CaseError(key, "polygon has zero area");
  if (area2 < 0.0) std::reverse(outline.begin(), outline.end());  // counter-clockwise in (x, z)
  return outline;
}

}  // namespace

Shape Shape::polygon(const std::vector<Eigen::Vector2d>& vertices, const std::string& key) {
  Shape s;
  s.kind_ = Kind::polygon;
  s.dimensions_ = 2;
  s.outline_ = checked_outline(vertices, key);
  for (const auto& t : triangulate(s.outline_, key))
    s.cells_.push_back({{edge_plane(t[0], t[1]), edge_plane(t[1], t[2]), edge_plane(t[2], t[0])}});
  const std::size_t n = s.outline_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = s.outline_[i];
    const auto& b = s.outline_[(i + 1) % n];
    s.faces_.push_back(Face::make({Vec3(a.x(), 0, a.y()), Vec3(b.x(), 0, b.y())}, edge_plane(a, b).normal));
    s.bounds_.extend(Vec3(a.x(), 0, a.y()));
  }
  s.bounds_.lo.y() = -kInf, s.bounds_.hi.y() = kInf;
  return s;
}

Shape Shape::extruded_polygon(const std::vector<Eigen::Vector2d>& vertices, double y_min, double y_max,
                              const std::string& key) {
  if (!(std::isfinite(y_min) && std::isfinite(y_max) && y_min < y_max))
    throw CaseError(key + ".y_max", "y_max must exceed y_min");
  Shape s;
  s.kind_ = Kind::extruded_polygon;
  s.dimensions_ = 3;
  s.outline_ = checked_outline(vertices, key + ".vertices");
  s.y_min_ = y_min, s.y_max_ = y_max;
  const Plane top{Vec3::UnitY(), y_max}, bottom{-Vec3::UnitY(), -y_min};
  for (const auto& t : triangulate(s.outline_, key + ".vertices")) {
    s.cells_.push_back({{edge_plane(t[0], t[1]), edge_plane(t[1], t[2]), edge_plane(t[2], t[0]), top, bottom}});
    for (double y : {y_min, y_max}) {  // the caps, as the triangles of the outline
      std::vector<Vec3> tri;
      for (const auto& p : t) tri.emplace_back(p.x(), y, p.y());
      s.faces_.push_back(Face::make(std::move(tri), Vec3(0.0, y == y_max ? 1.0 : -1.0, 0.0)));
    }
  }
  const std::size_t n = s.outline_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = s.outline_[i];
    const auto& b = s.outline_[(i + 1) % n];
    s.faces_.push_back(Face::make({Vec3(a.x(), y_min, a.y()), Vec3(b.x(), y_min, b.y()), Vec3(b.x(), y_max, b.y()),
                                   Vec3(a.x(), y_max, a.y())},
                                  edge_plane(a, b).normal));
    s.bounds_.extend(Vec3(a.x(), y_min, a.y()));
    s.bounds_.extend(Vec3(a.x(), y_max, a.y()));
  }
  return s;
}

Shape Shape::half_space(const std::vector<double>& point, const std::vector<double>& normal, int dimensions,
                        const Aabb& face_bounds, const std::string& key) {
  check_vector(point, dimensions, key + ".point");
  check_vector(normal, dimensions, key + ".normal");
  const Vec3 p = embed(point, dimensions);
  Vec3 n = embed(normal, dimensions);
  if (n.norm() == 0.0) throw CaseError(key + ".normal", "normal must not be zero");
  n.normalize();
  Shape s;
  s.kind_ = Kind::half_space;
  s.dimensions_ = dimensions;
  s.cells_ = {ConvexCell{{Plane{n, n.dot(p)}}}};
  s.bounds_ = Aabb::everything();
  // The face: the plane clipped to face_bounds (a square, or a segment in 2D, then the box).
  Aabb fb = face_bounds;
  if (dimensions == 2) fb.lo.y() = fb.hi.y() = 0.0;
  const Vec3 centre = 0.5 * (fb.lo + fb.hi);
  const Vec3 c = centre - n.dot(centre - p) * n;
  const double size = (fb.hi - fb.lo).norm() + (c - centre).norm() + 1.0;
  std::vector<Vec3> v;
  if (dimensions == 2) {
    const Vec3 t(-n.z(), 0.0, n.x());
    v = {c - size * t, c + size * t};
  } else {
    const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
    v = {c - size * u - size * w, c + size * u - size * w, c + size * u + size * w, c - size * u + size * w};
  }
  const ConvexCell clip_box = box_cells(fb.lo, fb.hi, dimensions)[0];
  for (const Plane& plane : clip_box.planes) {
    v = clip_vertices(v, plane);
    if (v.size() < 2) break;
  }
  if (!degenerate(v, 1e-12 * size, dimensions == 3)) s.faces_.push_back(Face::make(std::move(v), n));
  return s;
}

bool Shape::contains(const Vec3& x) const {
  switch (kind_) {
    case Kind::box:
    case Kind::half_space:
      return cells_[0].contains(x);
    case Kind::polygon:
      return crossing_test(outline_, x.x(), x.z());
    case Kind::extruded_polygon:
      return x.y() >= y_min_ && x.y() <= y_max_ && crossing_test(outline_, x.x(), x.z());
    case Kind::heightfield:
      if (x.x() < node_x_.front() || x.x() > node_x_.back()) return false;
      if (dimensions_ == 3 && (x.y() < node_y_.front() || x.y() > node_y_.back())) return false;
      return x.z() >= height(lower_, x.x(), x.y()) && x.z() <= height(upper_, x.x(), x.y());
    case Kind::mesh:
      return mesh_contains(x);
  }
  return false;
}

namespace {

// The node cell [v[c], v[c + 1]] holding t (within v's range), and t's fraction across it.
std::pair<std::size_t, double> node_cell(const std::vector<double>& v, double t) {
  if (v.size() == 1) return {0, 0.0};
  const std::size_t c =
      std::min<std::size_t>(std::upper_bound(v.begin(), v.end(), t) - v.begin(), v.size() - 1) - 1;
  return {c, (t - v[c]) / (v[c + 1] - v[c])};
}

}  // namespace

double Shape::height(const std::vector<double>& field, double x, double y) const {
  const std::size_t nx = node_x_.size();
  const auto [i, u] = node_cell(node_x_, x);
  if (dimensions_ == 2) return field[i] + u * (field[i + 1] - field[i]);
  const auto [j, v] = node_cell(node_y_, y);
  const double h00 = field[j * nx + i], h10 = field[j * nx + i + 1], h01 = field[(j + 1) * nx + i],
               h11 = field[(j + 1) * nx + i + 1];
  // The triangles (i, j) (i+1, j) (i+1, j+1) and (i, j) (i+1, j+1) (i, j+1).
  return u >= v ? h00 + u * (h10 - h00) + v * (h11 - h10) : h00 + u * (h11 - h01) + v * (h01 - h00);
}

Shape Shape::heightfield(std::vector<double> x, std::vector<double> y, std::vector<double> lower,
                         std::vector<double> upper, int dimensions, const std::string& key) {
  const std::size_t nx = x.size(), ny = y.size();
  if (nx < 2 || (dimensions == 3 && ny < 2) || (dimensions == 2 && ny != 1) || lower.size() != nx * ny ||
      upper.size() != nx * ny)
    throw CaseError(key, "a height field needs 2 or more nodes along each axis and a height at each node");
  for (std::size_t k = 0; k < lower.size(); ++k)
    if (!(lower[k] <= upper[k]) || !std::isfinite(lower[k]) || !std::isfinite(upper[k]))
      throw CaseError(key, "the lower surface must lie at or below the upper one at every node");
  Shape s;
  s.kind_ = Kind::heightfield;
  s.dimensions_ = dimensions;
  const auto point = [&](std::size_t i, std::size_t j, const std::vector<double>& field) {
    return Vec3(x[i], dimensions == 3 ? y[j] : 0.0, field[j * nx + i]);
  };
  // A face of the top (upper) or bottom (lower) surface and its plane, outward up or down.
  const auto surface_piece = [&](std::vector<Vec3> v, bool top, Plane* plane) {
    Vec3 n = dimensions == 3 ? Vec3((v[1] - v[0]).cross(v[2] - v[0])) : Vec3(-(v[1] - v[0]).z(), 0.0, (v[1] - v[0]).x());
    n.normalize();
    if ((n.z() < 0.0) == top) n = -n;
    *plane = {n, n.dot(v[0])};
    s.faces_.push_back(Face::make(std::move(v), n));
  };
  // A side face on the footprint's edge, where the layer has thickness.
  const auto side = [&](const Vec3& a, const Vec3& b, double a_low, double b_low, const Vec3& outward) {
    if (a.z() <= a_low && b.z() <= b_low) return;
    std::vector<Vec3> v;
    if (dimensions == 2) v = {Vec3(a.x(), 0.0, a_low), a};
    else {
      v = {Vec3(a.x(), a.y(), a_low), Vec3(b.x(), b.y(), b_low)};
      if (b.z() > b_low) v.push_back(b);
      if (a.z() > a_low) v.push_back(a);
    }
    s.faces_.push_back(Face::make(std::move(v), outward));
  };
  const bool flat_lower = std::all_of(lower.begin(), lower.end(), [&](double z) { return z == lower[0]; });

  if (dimensions == 2) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      ConvexCell cell;
      cell.planes = {{Vec3::UnitX(), x[i + 1]}, {-Vec3::UnitX(), -x[i]}};
      Plane top, bottom;
      surface_piece({point(i, 0, upper), point(i + 1, 0, upper)}, true, &top);
      surface_piece({point(i, 0, lower), point(i + 1, 0, lower)}, false, &bottom);
      cell.planes.push_back(top), cell.planes.push_back(bottom);
      s.cells_.push_back(std::move(cell));
    }
    side(point(0, 0, upper), point(0, 0, upper), lower[0], lower[0], -Vec3::UnitX());
    side(point(nx - 1, 0, upper), point(nx - 1, 0, upper), lower[nx - 1], lower[nx - 1], Vec3::UnitX());
  } else {
    for (std::size_t j = 0; j + 1 < ny; ++j)
      for (std::size_t i = 0; i + 1 < nx; ++i) {
        const std::array<std::array<std::size_t, 2>, 3> triangles[2] = {{{{i, j}, {i + 1, j}, {i + 1, j + 1}}},
                                                                         {{{i, j}, {i + 1, j + 1}, {i, j + 1}}}};
        for (const auto& t : triangles) {
          ConvexCell cell;
          std::vector<Vec3> up, down;
          for (int k = 0; k < 3; ++k) {
            up.push_back(point(t[k][0], t[k][1], upper));
            down.push_back(point(t[k][0], t[k][1], lower));
            const Vec3 a = point(t[k][0], t[k][1], upper), b = point(t[(k + 1) % 3][0], t[(k + 1) % 3][1], upper);
            const Vec3 out = Vec3(b.y() - a.y(), a.x() - b.x(), 0.0).normalized();  // right of a → b, counter-clockwise
            cell.planes.push_back({out, out.dot(a)});
          }
          Plane top, bottom;
          surface_piece(std::move(up), true, &top);
          if (flat_lower) bottom = {-Vec3::UnitZ(), -lower[0]};
          else surface_piece(std::move(down), false, &bottom);
          cell.planes.push_back(top), cell.planes.push_back(bottom);
          s.cells_.push_back(std::move(cell));
        }
      }
    if (flat_lower)  // one face for a flat bottom rather than two per node cell
      s.faces_.push_back(Face::make({Vec3(x[0], y[0], lower[0]), Vec3(x[nx - 1], y[0], lower[0]),
                                     Vec3(x[nx - 1], y[ny - 1], lower[0]), Vec3(x[0], y[ny - 1], lower[0])},
                                    -Vec3::UnitZ()));
    for (std::size_t i = 0; i + 1 < nx; ++i)
      for (std::size_t j : {std::size_t(0), ny - 1})
        side(point(i, j, upper), point(i + 1, j, upper), lower[j * nx + i], lower[j * nx + i + 1],
             Vec3(j == 0 ? -Vec3::UnitY() : Vec3(Vec3::UnitY())));
    for (std::size_t j = 0; j + 1 < ny; ++j)
      for (std::size_t i : {std::size_t(0), nx - 1})
        side(point(i, j, upper), point(i, j + 1, upper), lower[j * nx + i], lower[(j + 1) * nx + i],
             Vec3(i == 0 ? -Vec3::UnitX() : Vec3(Vec3::UnitX())));
  }
  s.bounds_.lo = Vec3(x.front(), dimensions == 3 ? y.front() : -kInf, *std::min_element(lower.begin(), lower.end()));
  s.bounds_.hi = Vec3(x.back(), dimensions == 3 ? y.back() : kInf, *std::max_element(upper.begin(), upper.end()));
  s.node_x_ = std::move(x), s.node_y_ = std::move(y), s.lower_ = std::move(lower), s.upper_ = std::move(upper);
  return s;
}

Shape Shape::translated(const Vec3& shift) const {
  Shape s = *this;
  for (auto& v : s.outline_) v += Eigen::Vector2d(shift.x(), shift.z());
  s.y_min_ += shift.y(), s.y_max_ += shift.y();
  for (double& x : s.node_x_) x += shift.x();
  if (dimensions_ == 3)
    for (double& y : s.node_y_) y += shift.y();
  for (double& z : s.lower_) z += shift.z();
  for (double& z : s.upper_) z += shift.z();
  for (auto& c : s.cells_) c = c.translated(shift);
  for (auto& b : s.cell_bounds_) b.lo += shift, b.hi += shift;
  for (auto& f : s.faces_) f = f.translated(shift);
  s.bounds_.lo += shift, s.bounds_.hi += shift;
  return s;
}

Shape shape_from_spec(const v1::Shape& spec, int dimensions, const Aabb& half_space_face_bounds,
                      const v1::TerrainGrid& terrain, double dp, const std::string& key) {
  auto outline = [](const auto& vertices) {
    std::vector<Eigen::Vector2d> v;
    for (const auto& p : vertices) v.emplace_back(p.x(), p.z());
    return v;
  };
  switch (spec.kind_case()) {
    case v1::Shape::kBox:
      return Shape::box({spec.box().min().begin(), spec.box().min().end()},
                        {spec.box().max().begin(), spec.box().max().end()}, dimensions, key + ".box");
    case v1::Shape::kPolygon:
      if (dimensions != 2) throw CaseError(key + ".polygon", "polygon is for 2D cases; use extruded_polygon in 3D");
      return Shape::polygon(outline(spec.polygon().vertices()), key + ".polygon.vertices");
    case v1::Shape::kExtrudedPolygon:
      if (dimensions != 3) throw CaseError(key + ".extruded_polygon", "extruded_polygon is for 3D cases");
      return Shape::extruded_polygon(outline(spec.extruded_polygon().vertices()), spec.extruded_polygon().y_min(),
                                     spec.extruded_polygon().y_max(), key + ".extruded_polygon");
    case v1::Shape::kHalfSpace:
      return Shape::half_space({spec.half_space().point().begin(), spec.half_space().point().end()},
                               {spec.half_space().normal().begin(), spec.half_space().normal().end()}, dimensions,
                               half_space_face_bounds, key + ".half_space");
    case v1::Shape::kTerrain: {
      if (terrain.nx() < 1) throw CaseError(key + ".terrain", "the case has no terrain (terrain.grid)");
      LayerSurfaces l = layer_surfaces(spec.terrain(), terrain, dimensions, dp, half_space_face_bounds.lo.z());
      return Shape::heightfield(std::move(l.x), std::move(l.y), std::move(l.lower), std::move(l.upper), dimensions,
                                key + ".terrain");
    }
    case v1::Shape::kMesh: {
      if (dimensions != 3) throw CaseError(key + ".mesh", "is a 3D shape; a 2D case uses polygon");
      const v1::SolidMesh& m = spec.mesh();
      std::vector<Vec3> vertices;
      for (int k = 0; k + 2 < m.vertices_size(); k += 3)
        vertices.emplace_back(m.vertices(k), m.vertices(k + 1), m.vertices(k + 2));
      std::vector<std::array<std::uint32_t, 3>> triangles;
      for (int k = 0; k + 2 < m.triangles_size(); k += 3)
        triangles.push_back({m.triangles(k), m.triangles(k + 1), m.triangles(k + 2)});
      return Shape::mesh(vertices, triangles, key + ".mesh");
    }
    case v1::Shape::KIND_NOT_SET:
      break;
  }
  throw CaseError(key, "set exactly one of box, polygon, extruded_polygon, half_space, terrain, mesh");
}

// ---------------------------------------------------------------------------------------------

bool Region::contains(const Vec3& x) const {
  if (!shape_.contains(x)) return false;
  for (const Shape& s : subtract_)
    if (s.contains(x)) return false;
  return true;
}

Region Region::translated(const Vec3& shift) const {
  std::vector<Shape> sub;
  for (const Shape& s : subtract_) sub.push_back(s.translated(shift));
  return Region(shape_.translated(shift), std::move(sub));
}

std::vector<Face> Region::surface(double gap) const {
  const double tolerance = 1e-3 * gap;
  std::vector<Face> out;
  auto shifted_back = [&](std::vector<Face> pieces, const Vec3& shift, bool flip) {
    for (Face& f : pieces) out.push_back(flip ? f.translated(shift).flipped() : f.translated(shift));
  };
  for (const Face& f : shape_.faces()) {
    std::vector<Face> pieces{f.translated(-gap * f.normal)};  // just inside the shape
    for (const Shape& s : subtract_) pieces = cut_by_cells(pieces, s.cells(), tolerance);
    shifted_back(std::move(pieces), gap * f.normal, false);
  }
  for (std::size_t k = 0; k < subtract_.size(); ++k) {
    for (const Face& f : subtract_[k].faces()) {
      // Just outside the subtracted shape: region material there makes the face a surface.
      std::vector<Face> pieces = clip_to_cells({f.translated(gap * f.normal)}, shape_.cells(), tolerance);
      for (std::size_t j = 0; j < subtract_.size(); ++j)
        if (j != k) pieces = cut_by_cells(pieces, subtract_[j].cells(), tolerance);
      shifted_back(std::move(pieces), -gap * f.normal, true);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------

namespace {

// Where a face lies against a cell's planes, taken in order: `untouched` when every vertex is
// inside (signed distance <= 0) each plane before one that has every vertex strictly outside, so
// that cutting the face by the cell leaves it as it is and clipping it to the cell leaves nothing;
// `apart` when some plane has every vertex strictly outside (clipping leaves nothing); `cut`
// otherwise. The test costs no allocation: a terrain's 10⁵ cells against a wall's faces made
// the exact clipping alone take minutes.
enum class Overlap { untouched, apart, cut };

Overlap overlap(const Face& face, const ConvexCell& cell) {
  bool straddled = false;  // a plane before has vertices on both sides
  for (const Plane& p : cell.planes) {
    bool inside = false, outside = false;
    for (const Vec3& v : face.vertices) (p.signed_distance(v) > 0.0 ? outside : inside) = true;
    if (outside && !inside) return straddled ? Overlap::apart : Overlap::untouched;
    straddled = straddled || outside;
  }
  return Overlap::cut;
}

}  // namespace

std::vector<Face> clip_to_cell(const Face& face, const ConvexCell& cell, double tolerance) {
  if (overlap(face, cell) != Overlap::cut) return {};
  std::vector<Vec3> v = face.vertices;
  for (const Plane& p : cell.planes) {
    v = clip_vertices(v, p);
    if (degenerate(v, tolerance, !face.is_segment())) return {};
  }
  return {with_vertices(face, std::move(v))};
}

std::vector<Face> cut_by_cell(const Face& face, const ConvexCell& cell, double tolerance) {
  std::vector<Face> pieces;
  std::vector<Vec3> rest = face.vertices;
  for (const Plane& p : cell.planes) {
    std::vector<Vec3> outside = clip_vertices(rest, Plane{-p.normal, -p.offset});
    if (!degenerate(outside, tolerance, !face.is_segment())) pieces.push_back(with_vertices(face, std::move(outside)));
    rest = clip_vertices(rest, p);
    if (degenerate(rest, tolerance, !face.is_segment())) break;  // nothing of the face left inside the cell
  }
  return pieces;
}

std::vector<Face> clip_to_cells(const std::vector<Face>& faces, const std::vector<ConvexCell>& cells,
                                double tolerance) {
  std::vector<Face> out;
  for (const Face& f : faces)
    for (const ConvexCell& c : cells)
      for (Face& piece : clip_to_cell(f, c, tolerance)) out.push_back(std::move(piece));
  return out;
}

std::vector<Face> cut_by_cells(const std::vector<Face>& faces, const std::vector<ConvexCell>& cells,
                               double tolerance) {
  std::vector<Face> pieces = faces, next;
  for (const ConvexCell& c : cells) {
    next.clear();
    for (Face& f : pieces) {
      if (overlap(f, c) == Overlap::untouched) next.push_back(std::move(f));
      else
        for (Face& piece : cut_by_cell(f, c, tolerance)) next.push_back(std::move(piece));
    }
    pieces.swap(next);
  }
  return pieces;
}

std::vector<Face> cut_by_region(const std::vector<Face>& faces, const Region& region, double tolerance) {
  // faces \ (S \ ∪T) = (faces \ S) ∪ (faces ∩ S ∩ ∪T)
  std::vector<Face> out = cut_by_cells(faces, region.shape().cells(), tolerance);
  std::vector<Face> rest = clip_to_cells(faces, region.shape().cells(), tolerance);
  for (const Shape& t : region.subtracted()) {
    for (Face& f : clip_to_cells(rest, t.cells(), tolerance)) out.push_back(std::move(f));
    rest = cut_by_cells(rest, t.cells(), tolerance);
  }
  return out;
}

}  // namespace cascade
