// The list of driver profiles (profiles_<family>.cpp define them).
#include <algorithm>

#include "drivers/profile.hpp"

namespace drivers {

std::string to_string(const Source& s) {
  return std::string(s.repo) + " " + std::string(s.path) + " @ " + std::string(s.ref);
}

bool Profile::serves(top::Model m) const noexcept {
  return std::find(models.begin(), models.end(), m) != models.end();
}

const std::vector<Profile>& profiles() {
  static const std::vector<Profile> all = {ardupilot_topotek(), ardupilot_skydroid(), pixeagle(),
                                           skydroid_gcs(), c10pro_tool()};
  return all;
}

const Profile* find_profile(std::string_view name) noexcept {
  for (const Profile& p : profiles())
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace drivers
