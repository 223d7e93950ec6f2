#include "meshik/option_names.h"

namespace meshik {

const char* feature_space_name(FeatureSpace feature_space) {
  return feature_space == FeatureSpace::kLinear ? "linear" : "nonlinear";
}

std::optional<FeatureSpace> feature_space_from_name(std::string_view name) {
  for (FeatureSpace candidate : {FeatureSpace::kNonlinear, FeatureSpace::kLinear})
    if (name == feature_space_name(candidate)) return candidate;
  return std::nullopt;
}

const char* blend_name(Blend blend) { return blend == Blend::kFree ? "free" : "affine"; }

std::optional<Blend> blend_from_name(std::string_view name) {
  for (Blend candidate : {Blend::kAffine, Blend::kFree})
    if (name == blend_name(candidate)) return candidate;
  return std::nullopt;
}

}  // namespace meshik
