#include "capture/synthetic_scenarios.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "capture/synthetic_texture.hpp"

namespace bmp::capture::synth {
namespace {

// Walks back and forth along x between lo and hi at height y from the last waypoint, heading first towards
// the far end in `direction` (+1 or -1), until past `until` seconds.
void pace(MoverScript& s, double lo, double hi, double y, double speed, int direction, double until) {
  while (s.path.back().t <= until) {
    const Waypoint& last = s.path.back();
    const double target = direction > 0 ? hi : lo;
    s.path.push_back({last.t + std::abs(target - last.p.x()) / speed, {target, y}});
    direction = -direction;
  }
}

// A mover that starts at x at time 0 and paces.
MoverScript pacer(MoverKind kind, int look, double lo, double hi, double x, double y, double speed,
                  int direction, double until) {
  MoverScript s;
  s.kind = kind;
  s.look = look;
  s.path.push_back({0.0, {x, y}});
  pace(s, lo, hi, y, speed, direction, until);
  return s;
}

// Where the scenarios put people: lanes at given distances ahead of the camera path's centre, across the
// room clear of the side furniture.
struct Stage {
  double camera_y = 0.0;
  double x_edge = 0.0;  // lanes run over [-x_edge, x_edge]
  double duration = 0.0;
  double speed = 1.0;
};

Stage stageOf(const SyntheticSceneConfig& c) {
  Stage st;
  st.camera_y = c.camera_centre[1];
  st.x_edge = c.room_size[0] / 2 - 0.8;
  st.duration = c.num_frames / c.fps;
  st.speed = c.walk_speed;
  return st;
}

ScenarioCast peopleWalking(const SyntheticSceneConfig& c, const Stage& st, SplitMix64& rng) {
  constexpr double kDistance[3] = {2.2, 2.8, 3.3};  // m ahead: people 400 to 270 pixels tall at 525 px
  ScenarioCast cast;
  for (int k = 0; k < std::min(c.num_moving_objects, 3); ++k) {
    const double y = st.camera_y + kDistance[k] + rng.uniform(-0.1, 0.1);
    const double x = rng.uniform(-st.x_edge, st.x_edge);
    const double speed = st.speed * rng.uniform(0.8, 1.2);
    cast.movers.push_back(
        pacer(MoverKind::kPerson, k, -st.x_edge, st.x_edge, x, y, speed, k % 2 == 0 ? 1 : -1, st.duration));
  }
  return cast;
}

ScenarioCast personStops(const Stage& st) {
  constexpr double kStandSeconds = 3.0;
  MoverScript s;
  s.kind = MoverKind::kPerson;
  const double y = st.camera_y + 2.6;
  const double from = -st.x_edge - 0.2;
  s.path.push_back({0.0, {from, y}});
  const double arrive = -from / st.speed;
  s.path.push_back({arrive, {0.0, y}});
  s.path.push_back({arrive + kStandSeconds, {0.0, y}});
  pace(s, from, -from, y, st.speed, 1, st.duration);
  ScenarioCast cast;
  cast.movers.push_back(s);
  return cast;
}

// Two rows of five cross the room through the side walls (as through doors), slowing down in the middle:
// while they pass the centre they cover most of the image.
ScenarioCast crowd(const Stage& st, double room_half_width, SplitMix64& rng) {
  constexpr double kRowDistance[2] = {1.7, 2.3};
  constexpr double kSpacing = 0.6, kSlowSeconds = 2.6;
  const double far = room_half_width + 2.1;  // every member beyond the wall
  const double fast = 1.3 * st.speed, slow = 0.3 * st.speed;
  const double t_in = (far - 0.4) / fast, t_slow = t_in + kSlowSeconds;
  const double x_slow = -0.4 + slow * kSlowSeconds;
  ScenarioCast cast;
  for (int k = 0; k < 10; ++k) {
    const int row = k / 5;
    const double dx = (k % 5 - 2) * kSpacing + row * kSpacing / 2 + rng.uniform(-0.05, 0.05);
    const double y = st.camera_y + kRowDistance[row] + rng.uniform(-0.05, 0.05);
    MoverScript s;
    s.kind = MoverKind::kPerson;
    s.look = k;
    s.path = {{0.0, {-far + dx, y}},
              {t_in, {-0.4 + dx, y}},
              {t_slow, {x_slow + dx, y}},
              {t_slow + (far - x_slow) / fast, {far + dx, y}}};
    cast.movers.push_back(s);
  }
  return cast;
}

ScenarioCast unknownMover(const Stage& st, SplitMix64& rng) {
  ScenarioCast cast;
  const double x_box = rng.uniform(-st.x_edge, 0.0), x_person = rng.uniform(0.0, st.x_edge);
  cast.movers.push_back(
      pacer(MoverKind::kBox, 0, -st.x_edge, st.x_edge, x_box, st.camera_y + 2.4, st.speed, 1, st.duration));
  cast.movers.push_back(pacer(MoverKind::kPerson, 0, -st.x_edge, st.x_edge, x_person, st.camera_y + 3.1,
                              0.9 * st.speed, -1, st.duration));
  return cast;
}

// The direction of the segment walked last up to segment i, or before any walking the first one to come.
double headingAt(const std::vector<Waypoint>& w, std::size_t i) {
  if (w.size() < 2) return 0.0;
  const auto heading = [&](std::size_t j, double& out) {
    const Eigen::Vector2d d = w[j + 1].p - w[j].p;
    if (d.norm() < 1e-9) return false;
    out = std::atan2(d.y(), d.x());
    return true;
  };
  double h = 0.0;
  for (std::size_t j = std::min(i, w.size() - 2) + 1; j-- > 0;)
    if (heading(j, h)) return h;
  for (std::size_t j = 0; j + 1 < w.size(); ++j)
    if (heading(j, h)) return h;
  return 0.0;
}

}  // namespace

ScenarioCast scenarioCast(const SyntheticSceneConfig& c) {
  if (c.scenario == SyntheticScenario::kBoxes)
    throw std::invalid_argument("synthetic scene: the boxes scenario is not scripted");
  if (c.people.empty())
    throw std::invalid_argument("synthetic scene: scenario " + toString(c.scenario) +
                                " needs at least one entry in 'people'");
  SplitMix64 rng(mixSeed(static_cast<uint64_t>(c.seed), 5));
  const Stage st = stageOf(c);
  ScenarioCast cast;
  if (c.num_moving_objects > 0) {
    switch (c.scenario) {
      case SyntheticScenario::kPeopleWalking:
        cast = peopleWalking(c, st, rng);
        break;
      case SyntheticScenario::kPersonStops:
        cast = personStops(st);
        break;
      case SyntheticScenario::kCrowd:
        cast = crowd(st, c.room_size[0] / 2, rng);
        break;
      default:
        cast = unknownMover(st, rng);
        break;
    }
  }
  // Person looks in turn; a photo used again is mirrored, so neighbours in a crowd differ.
  const int n = static_cast<int>(c.people.size());
  for (auto& m : cast.movers) {
    if (m.kind != MoverKind::kPerson) continue;
    const int slot = static_cast<int>(cast.looks.size());
    cast.looks.push_back({slot % n, (slot / n) % 2 == 1});
    m.look = slot;
  }
  return cast;
}

ScriptState scriptAt(const MoverScript& s, double t) {
  ScriptState out;
  const auto& w = s.path;
  std::size_t i = 0;  // the segment [w[i], w[i + 1]] holding t, or the last waypoint
  while (i + 1 < w.size() && w[i + 1].t <= t) ++i;
  if (i + 1 < w.size() && t >= w[i].t) {
    const double f = (t - w[i].t) / std::max(1e-9, w[i + 1].t - w[i].t);
    out.p = w[i].p + f * (w[i + 1].p - w[i].p);
    out.moving = (w[i + 1].p - w[i].p).norm() > 1e-9;
  } else {
    out.p = t < w.front().t ? w.front().p : w[i].p;
  }
  out.heading = headingAt(w, i);
  return out;
}

}  // namespace bmp::capture::synth

namespace bmp::capture {

const std::vector<std::string>& scenarioNames() {
  static const std::vector<std::string> names{"boxes", "people_walking", "person_stops", "crowd",
                                              "unknown_mover"};
  return names;
}

SyntheticScenario parseScenario(const std::string& name) {
  const auto& names = scenarioNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<SyntheticScenario>(it - names.begin());
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown scenario '" + name + "' (known: " + known + ")");
}

std::string toString(SyntheticScenario scenario) {
  return scenarioNames().at(static_cast<std::size_t>(scenario));
}

std::vector<PersonSource> defaultPeople() {
  // Full-length people in the shared sample photos; boxes from bmp-detect (yolov5n-640), widened to the
  // feet and elbows.
  return {{"images/bus.jpg", {50, 398, 160, 500}, 1.8},
          {"images/bus.jpg", {217, 398, 136, 472}, 1.75},
          {"images/person.jpg", {190, 98, 86, 276}, 1.7}};
}

}  // namespace bmp::capture
