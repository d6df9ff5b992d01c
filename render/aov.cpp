#include "render/aov.h"

#include <cassert>

namespace manylight {

const AovChannel& aovChannel(Aov aov) {
  for (const AovChannel& c : kAovChannels) {
    if (c.aov == aov) return c;
  }
  assert(false && "Aov::None has no channel");
  return kAovChannels[0];
}

std::vector<std::string> aovDefines(Aov aov) {
  if (aov == Aov::None) return {};
  return {"AOV", aovChannel(aov).define};
}

Aov parseAov(const std::string& name) {
  if (name.empty()) return Aov::None;
  std::string choices;
  for (const AovChannel& c : kAovChannels) {
    if (name == c.name) return c.aov;
    choices += (choices.empty() ? "" : ", ") + std::string(c.name);
  }
  throw Error("unknown AOV '" + name + "', expected one of " + choices);
}

std::vector<std::string> aovNames() {
  std::vector<std::string> names;
  for (const AovChannel& c : kAovChannels) names.emplace_back(c.name);
  return names;
}

}  // namespace manylight
