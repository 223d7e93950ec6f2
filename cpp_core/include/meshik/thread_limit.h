// The most threads an ExampleSet or a solve accepts: more is refused with InputError (OpenMP would
// try to allocate a team of that size and abort the host process). The Python API, the CLI and
// the plugins refuse the same count.
#pragma once

namespace meshik {

constexpr int kMaxThreads = 4096;

}  // namespace meshik
