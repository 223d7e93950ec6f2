// Registers meshik._core.decimate (the OpenMesh decimator, cpp_core/decimate) on the module.
// Called once from the module definition in core_module.cpp: bind_decimate(m);
#pragma once

#include <nanobind/nanobind.h>

void bind_decimate(nanobind::module_& m);
