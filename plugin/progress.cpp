#include "progress.h"

#include <algorithm>
#include <string>

namespace meshik::plugin {

ProgressCallback progressRange(vcg::CallBackPos* callback, int begin, int end) {
  return [callback, begin, end](double fraction, const std::string& stage) {
    if (callback == nullptr) return true;
    const double clamped = std::clamp(fraction, 0.0, 1.0);
    const std::string message = "MeshIK: " + stage;
    return callback(begin + static_cast<int>(clamped * (end - begin)), message.c_str());
  };
}

}  // namespace meshik::plugin
