#include "rktsph/geometry/triangle_mesher.hpp"

// CGAL's headers are found under /usr/include, a system directory, so their own warnings are not
// ours (-Werror stays on for this file).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include "rktsph/geometry/shapes.hpp"
#include "rktsph/geometry/triangle_node_sets.hpp"
#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact_predicates_tag: constraints of overlapping shapes may cross; their intersection points
// are then constructed (inexactly) and become vertices.
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Triangulation>;
using Face = Triangulation::Face_handle;
using Vertex = Triangulation::Vertex_handle;
using Point = Kernel::Point_2;

// The closed outline of a 2D shape, vertex by vertex.
std::vector<Point> shape_outline(const ShapeSpec& shape) {
  const std::vector<Vec3>& v = shape.vertices;
  if (shape.kind == ShapeSpec::Kind::Rectangle)
    return {Point(v[0][0], v[0][1]), Point(v[1][0], v[0][1]), Point(v[1][0], v[1][1]),
            Point(v[0][0], v[1][1])};
  std::vector<Point> points;
  for (const Vec3& vertex : v)
    points.emplace_back(vertex[0], vertex[1]);
  return points;
}

Vec3 centroid_of(const Face& face) {
  Vec3 c{};
  for (int k = 0; k < 3; ++k) {
    c[0] += face->vertex(k)->point().x() / 3.0;
    c[1] += face->vertex(k)->point().y() / 3.0;
  }
  return c;
}

double area_of(const Face& face) {
  return CGAL::to_double(
      CGAL::area(face->vertex(0)->point(), face->vertex(1)->point(), face->vertex(2)->point()));
}

// Marks the faces of the unrefined triangulation that lie in the union of the shapes. Every shape
// edge is a constraint, so each region the constraints enclose lies wholly inside or wholly
// outside every shape: one point per region decides it, the centroid of its largest face (the
// one least likely to be misjudged by rounding). The space between disjoint shapes is such a
// region, outside all of them, and stays out of the mesh (docs/theory.md §3.6).
void mark_domain(Triangulation& triangulation, const GeometrySpec& geometry) {
  std::map<Face, std::size_t> region;
  std::vector<Face> largest;
  std::vector<double> largest_area;
  std::vector<Face> stack;
  for (const Face start : triangulation.finite_face_handles()) {
    if (region.count(start) != 0) continue;
    const std::size_t id = largest.size();
    largest.push_back(start);
    largest_area.push_back(area_of(start));
    region[start] = id;
    stack.push_back(start);
    while (!stack.empty()) {
      const Face face = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const Face next = face->neighbor(k);
        if (face->is_constrained(k) || triangulation.is_infinite(next) || region.count(next) != 0)
          continue;
        region[next] = id;
        stack.push_back(next);
        const double area = area_of(next);
        if (area > largest_area[id]) {
          largest_area[id] = area;
          largest[id] = next;
        }
      }
    }
  }
  std::vector<bool> inside(largest.size());
  for (std::size_t id = 0; id < largest.size(); ++id)
    inside[id] = covering_shape(geometry, 2, centroid_of(largest[id]), 0.0) >= 0;
  for (const auto& [face, id] : region)
    face->set_in_domain(inside[id]);
}

using Segment = Kernel::Segment_2;

// Every edge of every shape, in the order of the shapes and their vertices.
std::vector<Segment> shape_edges(const GeometrySpec& geometry) {
  std::vector<Segment> edges;
  for (const ShapeSpec& shape : geometry.shapes) {
    const std::vector<Point> outline = shape_outline(shape);
    for (std::size_t k = 0; k < outline.size(); ++k)
      edges.emplace_back(outline[k], outline[(k + 1) % outline.size()]);
  }
  return edges;
}

// Whether edge `e` meets no other shape edge but at a shared end point (exact predicates), and
// meets those at 60° or more: such an edge gets a boundary layer; one that another edge crosses or
// overlaps, or that makes a sharp corner, is left to refinement.
std::vector<bool> free_edges(const std::vector<Segment>& edges) {
  std::vector<bool> free(edges.size(), true);
  for (std::size_t a = 0; a < edges.size(); ++a)
    for (std::size_t b = a + 1; b < edges.size(); ++b) {
      const Segment& s = edges[a];
      const Segment& t = edges[b];
      if (s.is_degenerate() || t.is_degenerate() || !CGAL::do_intersect(s, t)) continue;
      // Two edges of one vertex touch only there unless they run on along one line.
      bool only_at_vertex = false;
      for (const Point& p : {s.source(), s.target()})
        if (p == t.source() || p == t.target()) {
          const Point& other_s = p == s.source() ? s.target() : s.source();
          const Point& other_t = p == t.source() ? t.target() : t.source();
          only_at_vertex = !CGAL::collinear(p, other_s, other_t) ||
                           CGAL::angle(other_s, p, other_t) == CGAL::OBTUSE;
          // Two edges meeting at less than 60°, the angle below which Delaunay refinement is not
          // proven to end: refinement's own splitting about the corner (CGAL's clusters) is
          // kept there; with the edges split evenly beforehand it did not end on a 2:1 toe.
          const double ux = other_s.x() - p.x(), uy = other_s.y() - p.y();
          const double vx = other_t.x() - p.x(), vy = other_t.y() - p.y();
          if (ux * vx + uy * vy > 0.5 * std::hypot(ux, uy) * std::hypot(vx, vy))
            only_at_vertex = false;
        }
      if (!only_at_vertex) free[a] = free[b] = false;
    }
  return free;
}

// Points already placed, binned in squares of side `radius`, to refuse a new one nearer than
// `radius` to any of them.
class PointBins {
 public:
  explicit PointBins(double radius) : radius_(radius) {}
  void add(const Point& p) { bins_[key(p.x(), p.y())].push_back(p); }
  bool crowded(const Point& p) const {
    const auto [i, j] = key(p.x(), p.y());
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj) {
        const auto bin = bins_.find({i + di, j + dj});
        if (bin == bins_.end()) continue;
        for (const Point& q : bin->second)
          if (CGAL::squared_distance(p, q) < radius_ * radius_) return true;
      }
    return false;
  }

 private:
  std::pair<std::int64_t, std::int64_t> key(double x, double y) const {
    return {static_cast<std::int64_t>(std::floor(x / radius_)),
            static_cast<std::int64_t>(std::floor(y / radius_))};
  }
  double radius_;
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<Point>> bins_;
};

// The boundary layer (docs/theory.md §3.6): every free straight edge split into equal segments of
// about kBoundaryLayerSpacing h, and rows of points parallel to it on either side inside the
// shapes, row j at j s sqrt(3)/2 from the edge and staggered by s/2 from the row before, so that
// the triangles along the edge are near-equilateral and alike from one segment to the next (as
// the boundary layers of Gmsh). A row point is left out where it would fall nearer than
// kBoundaryLayerClearance s to another point or to a shape edge (at corners, where the layers of
// two edges meet); refinement fills those gaps. Returns the edges as polylines through their
// points (the constraints) and the row points, which smoothing keeps.
struct BoundaryLayer {
  std::vector<std::vector<Point>> constraints;
  std::vector<Point> rows;
};
BoundaryLayer boundary_layer(const GeometrySpec& geometry, double h, bool with_layer) {
  const std::vector<Segment> edges = shape_edges(geometry);
  BoundaryLayer layer;
  const double target = kBoundaryLayerSpacing * h;
  PointBins placed(kBoundaryLayerClearance * target);
  std::vector<double> spacing(edges.size(), 0.0);
  std::vector<bool> free = free_edges(edges);
  if (!with_layer) free.assign(edges.size(), false);  // the shapes' edges as they are
  // Only edges along an axis, whose split points and rows are exact in one coordinate: with the
  // layer on a slanted edge CGAL's refinement did not end (a point location that never returned,
  // on a quadrilateral with one slanted side; docs/theory.md §3.6).
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges[e].source().x() != edges[e].target().x() &&
        edges[e].source().y() != edges[e].target().y())
      free[e] = false;
  // An edge shorter than kBoundaryLayerShortest layer segments (the sides of a polygon drawn for
  // a circle) is left to refinement: with such edges split beforehand it did not end on a 48-gon.
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (std::sqrt(CGAL::to_double(edges[e].squared_length())) < kBoundaryLayerShortest * target)
      free[e] = false;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Point& a = edges[e].source();
    const Point& b = edges[e].target();
    const double length = std::sqrt(CGAL::to_double(edges[e].squared_length()));
    const int count =
        free[e] ? std::max(1, static_cast<int>(std::ceil(length / target - 1e-9))) : 1;
    spacing[e] = length / count;
    std::vector<Point> polyline{a};
    // a + t (b - a) keeps a coordinate exactly where the edge is parallel to an axis (x = 0 of a
    // mirror plane stays 0).
    for (int k = 1; k < count; ++k) {
      const double t = static_cast<double>(k) / count;
      polyline.emplace_back(a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));
    }
    polyline.push_back(b);
    for (const Point& p : polyline)
      if (!placed.crowded(p)) placed.add(p);
    layer.constraints.push_back(std::move(polyline));
  }
  for (int row = 1; row <= kBoundaryLayerRows; ++row)
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!free[e] || edges[e].is_degenerate()) continue;
      const Point& a = edges[e].source();
      const Point& b = edges[e].target();
      const double s = spacing[e];
      const double length = std::sqrt(CGAL::to_double(edges[e].squared_length()));
      const int count = static_cast<int>(std::lround(length / s));
      const double tx = (b.x() - a.x()) / length, ty = (b.y() - a.y()) / length;
      const double offset = row * s * std::sqrt(3.0) / 2.0;
      const double stagger = (row % 2 == 1) ? 0.5 : 0.0;
      for (const double side : {1.0, -1.0})
        for (int k = 0; k <= count; ++k) {
          const double along = (k + stagger) * s;
          if (along <= 0.0 || along >= length) continue;
          const Point p(a.x() + along * tx - side * offset * ty,
                        a.y() + along * ty + side * offset * tx);
          if (covering_shape(geometry, 2, {p.x(), p.y(), 0.0}, 0.0) < 0 || placed.crowded(p))
            continue;
          bool clear = true;
          for (const Segment& edge : edges)
            if (CGAL::squared_distance(p, edge) <
                std::pow(kBoundaryLayerClearance * s * std::sqrt(3.0) / 2.0, 2)) {
              clear = false;
              break;
            }
          if (!clear) continue;
          placed.add(p);
          layer.rows.push_back(p);
        }
    }
  return layer;
}

// Delaunay refinement of the marked domain to edges at most h and angles at least
// arcsin(sqrt(B)) but where an input angle is smaller, one insertion at a time; false if the
// triangulation passes `vertex_limit` vertices first (refinement that does not end: the layer's
// points beside a corner refinement must split ever finer, §3.6).
bool refine_within(Triangulation& triangulation, double h, std::size_t vertex_limit) {
  CGAL::Delaunay_mesher_2<Triangulation, Criteria> mesher(triangulation,
                                                          Criteria(kTriangleShapeBound, h));
  mesher.init(true);
  while (!mesher.is_refinement_done()) {
    if (triangulation.number_of_vertices() > vertex_limit) return false;
    mesher.step_by_step_refine_mesh();
  }
  return true;
}

// The shapes' edges as constraints, with their boundary layer when `with_layer`, the domain
// marked, and refinement. Returns the layer's row vertices, or nothing if the refinement with the
// layer passed `vertex_limit` vertices (the caller then meshes again without it).
std::optional<std::vector<Vertex>> mesh_shapes(Triangulation& triangulation,
                                               const GeometrySpec& geometry, bool with_layer,
                                               std::size_t vertex_limit) {
  const BoundaryLayer layer = boundary_layer(geometry, geometry.spacing, with_layer);
  for (const std::vector<Point>& polyline : layer.constraints)
    for (std::size_t k = 0; k + 1 < polyline.size(); ++k)
      triangulation.insert_constraint(polyline[k], polyline[k + 1]);
  std::vector<Vertex> rows;
  for (const Point& p : layer.rows)
    rows.push_back(triangulation.insert(p));
  mark_domain(triangulation, geometry);
  if (!refine_within(triangulation, geometry.spacing, vertex_limit)) return std::nullopt;
  return rows;
}

// A bound of the vertices a refinement that ends makes: twenty times the equilateral triangles of
// edge h over the shapes' bounding box (a mesh of the bundled cases has about one vertex per such
// triangle), and no fewer than 2000. Past it the layer is dropped, not the case.
std::size_t refinement_vertex_limit(const GeometrySpec& geometry) {
  double x_min = std::numeric_limits<double>::infinity(), y_min = x_min;
  double x_max = -x_min, y_max = -x_min;
  for (const Segment& edge : shape_edges(geometry))
    for (const Point& p : {edge.source(), edge.target()}) {
      x_min = std::min(x_min, p.x()), x_max = std::max(x_max, p.x());
      y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
    }
  const double h = geometry.spacing;
  const double triangles = (x_max - x_min) * (y_max - y_min) / (std::sqrt(3.0) / 4.0 * h * h);
  return static_cast<std::size_t>(std::max(2000.0, 20.0 * triangles));
}

double signed_area(const Point& a, const Point& b, const Point& c) {
  return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y()));
}

// The smallest squared sine of the corners of triangle abc, its longest squared edge and its
// squared width (the smallest altitude, 2A over the longest edge: §4.8).
struct TriangleShape {
  double sine = 0.0, longest = 0.0, width = 0.0;
};
TriangleShape shape_of(const Point& a, const Point& b, const Point& c) {
  const double ab = CGAL::squared_distance(a, b), bc = CGAL::squared_distance(b, c),
               ca = CGAL::squared_distance(c, a);
  const double twice_area = 2.0 * signed_area(a, b, c);
  // sin of the corner between edges e and f: 2A / (|e| |f|); the smallest is opposite the shortest
  // edge, between the two longest.
  const double longest = std::max({ab, bc, ca});
  const double middle = ab + bc + ca - longest - std::min({ab, bc, ca});
  if (!(twice_area > 0.0)) return {-1.0, longest, 0.0};
  return {twice_area * twice_area / (longest * middle), longest, twice_area * twice_area / longest};
}

// Centroidal smoothing of a refined mesh (docs/theory.md §3.6): every free vertex (one on no
// shape edge and not of the boundary layer's rows, `kept`, all of whose triangles are in the
// domain) moves towards the centroid of the polygon
// its triangles make, sweep after sweep, the others staying; the triangles are kept, only their
// corners move. Refinement leaves vertices crowded beside the constraints, thin triangles whose
// width sets the time step (§4.8), and node patches so lopsided that the nodal strain average is
// biased (§4.8, *Measured*). A move is made only if the vertex's triangles keep the refinement's
// guarantees (every edge at most h, every angle above the bound or no smaller than before), or
// else half of it, or a quarter; so the mesh stays as good as refinement made it, and is still a
// valid triangulation of the shapes (though no longer exactly Delaunay). Written here rather than
// taken from CGAL's Lloyd optimiser, whose sums run in an order set by memory addresses, so that
// two builds of one case differed in the last bits, and which lengthens edges past h: here every
// sum runs in an order fixed by the positions alone, so a case meshes to the same bits every time.
void smooth_free_vertices(Triangulation& triangulation, double h, const std::vector<Vertex>& kept) {
  const std::set<Vertex> fixed(kept.begin(), kept.end());
  std::vector<Vertex> vertices;
  for (const Vertex vertex : triangulation.finite_vertex_handles())
    vertices.push_back(vertex);
  std::sort(vertices.begin(), vertices.end(), [](const Vertex& a, const Vertex& b) {
    const Point& p = a->point();
    const Point& q = b->point();
    return p.y() != q.y() ? p.y() < q.y() : p.x() < q.x();
  });
  // The star of each free vertex: its triangles' two other corners, counter-clockwise, the
  // triangles in the order of those corners' places in the sorted list.
  std::map<Vertex, std::size_t> index;
  for (std::size_t i = 0; i < vertices.size(); ++i)
    index[vertices[i]] = i;
  std::vector<std::pair<Vertex, std::vector<std::array<Vertex, 2>>>> stars;
  for (const Vertex& vertex : vertices) {
    if (triangulation.are_there_incident_constraints(vertex) || fixed.count(vertex) != 0) continue;
    std::vector<std::array<Vertex, 2>> star;
    bool free = true;
    auto face = triangulation.incident_faces(vertex);
    const auto end = face;
    do {
      if (triangulation.is_infinite(face) || !face->is_in_domain()) {
        free = false;
        break;
      }
      const int k = face->index(vertex);
      star.push_back({face->vertex(Triangulation::ccw(k)), face->vertex(Triangulation::cw(k))});
    } while (++face != end);
    if (!free) continue;
    std::sort(star.begin(), star.end(), [&index](const auto& s, const auto& t) {
      return std::make_pair(index.at(s[0]), index.at(s[1])) <
             std::make_pair(index.at(t[0]), index.at(t[1]));
    });
    stars.emplace_back(vertex, std::move(star));
  }
  const double longest_allowed = h * h;
  // Whether the star keeps the guarantees with its centre at p: every triangle counter-clockwise,
  // no edge longer than h, no corner sharper than the bound or than the star's sharpest now, and
  // no triangle narrower than the star's narrowest now (the time step's width, §4.8).
  const auto acceptable = [&](const std::vector<std::array<Vertex, 2>>& star, const Point& p,
                              const TriangleShape& worst_now) {
    for (const auto& [b, c] : star) {
      const TriangleShape shape = shape_of(p, b->point(), c->point());
      if (shape.sine <= 0.0 || shape.longest > longest_allowed ||
          shape.sine < std::min(kTriangleShapeBound, worst_now.sine) ||
          shape.width < worst_now.width)
        return false;
    }
    return true;
  };
  for (int sweep = 0; sweep < kSmoothingSweeps; ++sweep)
    for (const auto& [vertex, star] : stars) {
      const Point here = vertex->point();
      double area = 0.0, x = 0.0, y = 0.0;
      TriangleShape worst{1.0, 0.0, std::numeric_limits<double>::infinity()};
      for (const auto& [b, c] : star) {
        const Point& pb = b->point();
        const Point& pc = c->point();
        const double a = signed_area(here, pb, pc);
        area += a;
        x += a * (here.x() + pb.x() + pc.x()) / 3.0;
        y += a * (here.y() + pb.y() + pc.y()) / 3.0;
        const TriangleShape shape = shape_of(here, pb, pc);
        worst.sine = std::min(worst.sine, shape.sine);
        worst.width = std::min(worst.width, shape.width);
      }
      if (!(area > 0.0)) continue;
      double step = 1.0;
      for (int attempt = 0; attempt < 3; ++attempt, step *= 0.5) {
        const Point moved(here.x() + step * (x / area - here.x()),
                          here.y() + step * (y / area - here.y()));
        if (acceptable(star, moved, worst)) {
          vertex->set_point(moved);
          break;
        }
      }
    }
}

}  // namespace

NodeSets build_triangle_node_sets(const GeometrySpec& geometry,
                                  const std::vector<std::string>& material_names) {
  const double h = geometry.spacing;
  const double tolerance = kSpacingTolerance * h;
  Triangulation triangulation;
  for (const ShapeSpec& shape : geometry.shapes)
    if (shape.kind == ShapeSpec::Kind::Segment)
      throw InputError(shape.where, "geometry.cells", "triangles",
                       "triangle cells exist only in 2D", "lattice in 1D");
  try {
    // The boundary layer beside some corners leaves refinement no end (§3.6): there the shapes
    // are meshed again without it, as refinement alone always ends.
    const std::size_t limit = refinement_vertex_limit(geometry);
    std::optional<std::vector<Vertex>> layer = mesh_shapes(triangulation, geometry, true, limit);
    if (!layer) {
      triangulation.clear();
      layer = mesh_shapes(triangulation, geometry, false, std::numeric_limits<std::size_t>::max());
    }
    smooth_free_vertices(triangulation, h, *layer);
  } catch (const CGAL::Failure_exception& failure) {
    // A CGAL precondition the reader's checks let through (e.g. coordinates so large that the
    // inexact constructions overflow): the shapes' fault, said as such rather than a crash.
    throw InputError(
        geometry.where, "geometry.shapes", "",
        fmt::format("the triangle mesher (CGAL) failed on these shapes: {}", failure.what()),
        "shapes of moderate coordinates whose edges cross at clear angles");
  }

  // The triangles kept: those of the domain whose centroid a shape covers (the material's).
  std::vector<std::pair<Face, std::int32_t>> kept;
  for (const Face face : triangulation.finite_face_handles()) {
    if (!face->is_in_domain()) continue;
    const int shape = covering_shape(geometry, 2, centroid_of(face), tolerance);
    if (shape >= 0) kept.emplace_back(face, shape_material(geometry, shape, material_names));
  }
  if (kept.empty())
    throw InputError(geometry.where, "geometry.shapes", "", "the shapes hold no triangle",
                     "shapes of non-zero area");

  // Nodes: the corners of the kept triangles, numbered by (y, x) whatever CGAL's order.
  std::vector<Vertex> corners;
  for (const auto& [face, material] : kept)
    for (int k = 0; k < 3; ++k)
      corners.push_back(face->vertex(k));
  const auto by_y_then_x = [](const Vertex& a, const Vertex& b) {
    const Point& p = a->point();
    const Point& q = b->point();
    return p.y() != q.y() ? p.y() < q.y() : p.x() < q.x();
  };
  std::sort(corners.begin(), corners.end(), by_y_then_x);
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::map<Vertex, std::int32_t> node_of;
  for (std::size_t i = 0; i < corners.size(); ++i)
    node_of[corners[i]] = static_cast<std::int32_t>(i);

  // Triangles: corners counter-clockwise, as CGAL keeps them (triangle_node_sets orders them).
  std::vector<MeshTriangle> triangles;
  triangles.reserve(kept.size());
  for (const auto& [face, material] : kept)
    triangles.push_back(
        {{node_of.at(face->vertex(0)), node_of.at(face->vertex(1)), node_of.at(face->vertex(2))},
         material});

  std::vector<Vec3> points;
  std::vector<std::int32_t> node_material;
  points.reserve(corners.size());
  for (const Vertex& vertex : corners) {
    const Vec3 x{vertex->point().x(), vertex->point().y(), 0.0};
    points.push_back(x);
    const int shape = covering_shape(geometry, 2, x, tolerance);
    // A corner is in its triangles, so a shape covers it; -1 only if rounding put it a hair
    // outside, when the material of its first triangle stands in.
    node_material.push_back(shape >= 0 ? shape_material(geometry, shape, material_names) : -1);
  }
  NodeSets nodes =
      triangle_node_sets(points, std::move(node_material), std::move(triangles), h, material_names);
  check_cells(nodes, geometry);
  return nodes;
}

}  // namespace rktsph
