#include "pose_state.h"

#include <algorithm>

namespace meshik::edit {

std::vector<int> groupMembers(const std::vector<int>& groups, int group) {
  std::vector<int> members;
  for (size_t h = 0; h < groups.size(); ++h)
    if (groups[h] == group) members.push_back(static_cast<int>(h));
  return members;
}

int newGroupNumber(const std::vector<int>& groups) {
  return groups.empty() ? 1 : *std::max_element(groups.begin(), groups.end()) + 1;
}

}  // namespace meshik::edit
