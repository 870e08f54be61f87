// Every sampler of the core as a type-erased entry (double precision), so the sampler claims run
// one harness over all of them: sample, standalone pdf, and which incidences the sampler accepts.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/samplers/sample.h"

namespace glintlab::verify {

struct SamplerEntry {
  std::string name;         // e.g. "heitz_vndf/ggx"
  bool ggx;                 // NDF: GGX (true) or Beckmann
  bool allows_backfacing;   // accepts ωi.z ≤ 0 (a back-facing shading normal)
  std::function<MicrofacetSample<double>(double ax, double ay, Vec3<double> wi, Vec2<double> u)> sample;
  std::function<double(double ax, double ay, Vec3<double> wi, Vec3<double> wo)> pdf;
  // eval: the BRDF with F = 1 (the same for every sampler of one NDF), for weight checks.
  std::function<double(double ax, double ay, Vec3<double> wi, Vec3<double> wo)> brdf;
};

const std::vector<SamplerEntry>& sampler_table();

}  // namespace glintlab::verify
