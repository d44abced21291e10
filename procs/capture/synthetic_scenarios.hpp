#pragma once
// The scripted movers of the people scenarios (SyntheticScenario other than kBoxes, whose walkers keep
// their elliptic loops in synthetic_geometry): each mover follows waypoints in time on the floor, walking
// straight between them and standing where two consecutive waypoints coincide.
#include <vector>

#include "capture/synthetic_scene.hpp"

namespace bmp::capture::synth {

struct Waypoint {
  double t = 0.0;  // s
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
};

struct MoverScript {
  MoverKind kind = MoverKind::kPerson;
  int look = 0;                // person: index into the scene's cut-outs; box: its walker index
  std::vector<Waypoint> path;  // increasing times; the mover stands at the ends before and after
};

// A look for a person mover: which configured person, and whether mirrored (a crowd reuses photos).
struct PersonLook {
  int person = 0;
  bool mirror = false;
};

struct ScenarioCast {
  std::vector<MoverScript> movers;  // in id order
  std::vector<PersonLook> looks;    // indexed by MoverScript::look of the person movers
};

// The movers of a scenario, deterministic from config.seed. Throws std::invalid_argument when the scenario
// needs people and config.people is empty, or for kBoxes (not scripted).
ScenarioCast scenarioCast(const SyntheticSceneConfig& config);

// A mover at time t: where it is, the direction it faces when walking, and whether it walks.
struct ScriptState {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  double heading = 0.0;  // radians about world z, of its last walked segment
  bool moving = false;
};
ScriptState scriptAt(const MoverScript& script, double t);

}  // namespace bmp::capture::synth
