#include "photon/radiosity_field.h"

namespace photon {
namespace {

RadiosityPower scaled(const RadiosityPower& p, float s) {
  return {p.direct * s, p.caustic * s, p.indirect * s};
}

void add(RadiosityPower* a, const RadiosityPower& b) {
  a->direct += b.direct;
  a->caustic += b.caustic;
  a->indirect += b.indirect;
}

}  // namespace

RadiosityField::RadiosityField(const RadiosityMesh& mesh,
                               const std::vector<RadiosityPower>& side_power) {
  const size_t elements = mesh.element_count();
  if (side_power.size() != 2 * elements) return;
  element_.resize(2 * elements);
  vertex_.assign(2 * mesh.vertex_count(), RadiosityPower{});
  std::vector<double> vertex_area(mesh.vertex_count(), 0.0);
  for (uint32_t e = 0; e < elements; ++e) {
    const float area = mesh.area(e);
    for (uint32_t side = 0; side < 2; ++side)
      element_[2 * e + side] = scaled(side_power[2 * e + side], area > 0.0f ? 1.0f / area : 0.0f);
    // Sum of P over the elements around a vertex / sum of their areas = area-weighted mean B.
    uint32_t vertex[3];
    bool flip[3];
    mesh.element_vertices(e, vertex, flip);
    for (int k = 0; k < 3; ++k) {
      vertex_area[vertex[k]] += area;
      for (uint32_t side = 0; side < 2; ++side)
        add(&vertex_[2 * vertex[k] + (side ^ (flip[k] ? 1u : 0u))], side_power[2 * e + side]);
    }
  }
  for (size_t v = 0; v < vertex_area.size(); ++v) {
    const float inv = vertex_area[v] > 0.0 ? static_cast<float>(1.0 / vertex_area[v]) : 0.0f;
    vertex_[2 * v] = scaled(vertex_[2 * v], inv);
    vertex_[2 * v + 1] = scaled(vertex_[2 * v + 1], inv);
  }
}

RadiosityPower RadiosityField::radiosity_at(const RadiosityLocation& where, uint32_t side) const {
  RadiosityPower b;
  if (empty()) return b;
  for (int k = 0; k < 3; ++k)
    add(&b,
        scaled(vertex_[2 * where.vertex[k] + (side ^ (where.flip[k] ? 1u : 0u))], where.weight[k]));
  return b;
}

}  // namespace photon
