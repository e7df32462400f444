// Parse an SDFormat file with libsdformat's own parser, strictly: warnings, unrecognized
// and deprecated elements are errors. Prints a summary line; exits 1 on any error.
// Built by tests/emit/test_sdf.py against whichever libsdformat pkg-config finds.
#include <sdf/sdf.hh>

#include <iostream>

int main(int argc, char **argv) {
  if (argc != 2) {
    std::cerr << "usage: sdformat_check FILE.sdf" << std::endl;
    return 2;
  }
  sdf::ParserConfig config;
  config.SetWarningsPolicy(sdf::EnforcementPolicy::ERR);
  config.SetUnrecognizedElementsPolicy(sdf::EnforcementPolicy::ERR);
  config.SetDeprecatedElementsPolicy(sdf::EnforcementPolicy::ERR);
  sdf::Root root;
  sdf::Errors errors = root.Load(argv[1], config);
  for (const auto &error : errors) std::cerr << error << std::endl;
  if (!errors.empty() || root.WorldCount() != 1) return 1;
  const sdf::World *world = root.WorldByIndex(0);
  const sdf::Model *building = world->ModelByName("building");
  if (building == nullptr || building->LinkCount() != 1) return 1;
  const sdf::Link *walls = building->LinkByIndex(0);
  std::cout << "models " << world->ModelCount() << " frames " << world->FrameCount() << " collisions "
            << walls->CollisionCount() << " visuals " << walls->VisualCount() << " static "
            << building->Static() << std::endl;
  return 0;
}
