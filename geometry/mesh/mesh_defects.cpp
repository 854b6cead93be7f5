#include "geometry/mesh/mesh_defects.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <vector>

#include "geometry/core/disjoint_sets.h"
#include "geometry/mesh/welding.h"

namespace skyband {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

}  // namespace

bool MeshDefects::any() const {
  return duplicate_vertex_positions || unreferenced_vertices || degenerate_index_triangles || zero_area_triangles ||
         duplicate_triangles || boundary_edges || non_manifold_edges || inconsistently_oriented_edges || non_manifold_vertices;
}

std::string MeshDefects::summary() const {
  std::string s;
  auto add = [&](std::size_t n, const char* what) {
    if (n == 0) return;
    if (!s.empty()) s += ", ";
    s += std::to_string(n) + ' ' + what;
  };
  add(duplicate_vertex_positions, "duplicate vertex positions (welded)");
  add(unreferenced_vertices, "unreferenced vertices");
  add(degenerate_index_triangles, "triangles with a repeated vertex index");
  add(zero_area_triangles, "zero-area triangles");
  add(duplicate_triangles, "duplicate triangles");
  add(boundary_edges, "boundary edges");
  add(non_manifold_edges, "non-manifold edges");
  add(inconsistently_oriented_edges, "inconsistently oriented edges");
  add(non_manifold_vertices, "non-manifold vertices");
  return s.empty() ? std::string("no defects") : s;
}

MeshDefects analyse_defects(const TriangleSoup& soup) {
  MeshDefects d;
  const std::size_t nv = soup.vertices.size();

  // Weld exactly equal positions.
  const std::vector<std::uint32_t> weld = weld_positions(soup.vertices);
  std::vector<std::uint32_t> multiplicity;
  for (const std::uint32_t w : weld) {
    if (w >= multiplicity.size()) multiplicity.resize(w + 1, 0);
    ++multiplicity[w];
  }
  d.welded_vertices = multiplicity.size();
  for (const std::uint32_t m : multiplicity)
    if (m > 1) {
      ++d.duplicate_vertex_positions;
      d.vertices_in_duplicate_positions += m;
    }

  std::vector<char> referenced(nv, 0);
  struct DirectedEdge {
    std::uint32_t lo, hi;
    bool forward;  // traversed lo→hi
  };
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * soup.triangles.size());
  struct Corner {
    std::uint32_t vertex, a, b;  // triangle (vertex, a, b) seen from `vertex`
  };
  std::vector<Corner> corners;
  corners.reserve(3 * soup.triangles.size());
  std::vector<std::array<std::uint32_t, 3>> vertex_sets;
  vertex_sets.reserve(soup.triangles.size());

  for (const auto& t : soup.triangles) {
    for (const std::uint32_t i : t) referenced[i] = 1;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) ++d.degenerate_index_triangles;
    const Vec3 &p = soup.vertices[t[0]], &q = soup.vertices[t[1]], &r = soup.vertices[t[2]];
    if (CGAL::collinear(Kernel::Point_3(p.x(), p.y(), p.z()), Kernel::Point_3(q.x(), q.y(), q.z()),
                        Kernel::Point_3(r.x(), r.y(), r.z())))
      ++d.zero_area_triangles;

    const std::array<std::uint32_t, 3> w{weld[t[0]], weld[t[1]], weld[t[2]]};
    std::array<std::uint32_t, 3> sorted = w;
    std::sort(sorted.begin(), sorted.end());
    vertex_sets.push_back(sorted);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = w[static_cast<std::size_t>(k)], b = w[static_cast<std::size_t>((k + 1) % 3)];
      if (a != b) edges.push_back({std::min(a, b), std::max(a, b), a < b});
    }
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2])
      for (int k = 0; k < 3; ++k)
        corners.push_back(
            {w[static_cast<std::size_t>(k)], w[static_cast<std::size_t>((k + 1) % 3)], w[static_cast<std::size_t>((k + 2) % 3)]});
  }
  for (const char r : referenced)
    if (!r) ++d.unreferenced_vertices;

  std::sort(vertex_sets.begin(), vertex_sets.end());
  for (std::size_t i = 1; i < vertex_sets.size(); ++i)
    if (vertex_sets[i] == vertex_sets[i - 1]) ++d.duplicate_triangles;

  std::sort(edges.begin(), edges.end(),
            [](const DirectedEdge& x, const DirectedEdge& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi; });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i, forward = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) forward += edges[j++].forward;
    const std::size_t count = j - i;
    if (count == 1) ++d.boundary_edges;
    if (count > 2) ++d.non_manifold_edges;
    if (count == 2 && forward != 1) ++d.inconsistently_oriented_edges;
    i = j;
  }

  // Non-manifold vertices: the triangles around a vertex are linked through shared edges
  // (vertex, x); more than one connected group is more than one fan.
  std::sort(corners.begin(), corners.end(), [](const Corner& x, const Corner& y) { return x.vertex < y.vertex; });
  std::vector<std::uint32_t> link;
  for (std::size_t i = 0; i < corners.size();) {
    std::size_t j = i;
    while (j < corners.size() && corners[j].vertex == corners[i].vertex) ++j;
    link.clear();
    for (std::size_t k = i; k < j; ++k) {
      link.push_back(corners[k].a);
      link.push_back(corners[k].b);
    }
    std::sort(link.begin(), link.end());
    link.erase(std::unique(link.begin(), link.end()), link.end());
    DisjointSets sets(link.size());
    auto local = [&](std::uint32_t v) {
      return static_cast<std::uint32_t>(std::lower_bound(link.begin(), link.end(), v) - link.begin());
    };
    for (std::size_t k = i; k < j; ++k) sets.unite(local(corners[k].a), local(corners[k].b));
    std::size_t fans = 0;
    for (std::uint32_t k = 0; k < link.size(); ++k)
      if (sets.find(k) == k) ++fans;
    if (fans > 1) ++d.non_manifold_vertices;
    i = j;
  }
  return d;
}

}  // namespace skyband
