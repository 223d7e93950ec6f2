// The names of the solver's enumerated options, as constraint files, the Python bindings and the
// MeshLab filters write them: one table, so every adapter reads and prints the same words.
#pragma once

#include <optional>
#include <string_view>

#include "meshik/meshik.h"

namespace meshik {

// "nonlinear" or "linear".
const char* feature_space_name(FeatureSpace feature_space);
// The FeatureSpace named `name` ("nonlinear" / "linear"); nullopt for any other text.
std::optional<FeatureSpace> feature_space_from_name(std::string_view name);

// "affine" or "free".
const char* blend_name(Blend blend);
// The Blend named `name` ("affine" / "free"); nullopt for any other text.
std::optional<Blend> blend_from_name(std::string_view name);

}  // namespace meshik
