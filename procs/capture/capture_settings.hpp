#pragma once
// bmp-capture's settings, typed: read and checked in one place from the "capture" section of capture.yaml
// and the command line (which wins). The defaults below are the only ones.
#include <string>
#include <vector>

#include "bmp/common/arg_parser.hpp"
#include "bmp/common/config.hpp"
#include "bmp/lcm/channels.hpp"  // channel names only: no LCM
#include "capture/pacer.hpp"
#include "capture/tum_source.hpp"

namespace bmp::capture {

// How frames are played: what the FramePlayer needs.
struct PlayerOptions {
  std::string channel = channels::kFrames;
  // Lockstep: the next frame goes out once every one of these channels has answered this one (a slam_pose_t
  // or detections_t carrying its seq), so the slowest consumer sets the pace and none falls behind.
  std::vector<std::string> ack_channels{channels::kPose};
  RateMode mode = RateMode::kRealtime;
  double speed = 1.0;               // realtime: recorded rate x speed
  double lockstep_timeout_s = 5.0;  // lockstep: give up waiting for an answer after this long
  // Lockstep: a frame whose answers are late is published again (a large message from anyone can overflow
  // the receivers' socket buffers, and the frame or its answer is lost): after this factor times the
  // median answer time of recent frames, and never sooner than the minimum.
  double lockstep_resend_factor = 4.0;
  double lockstep_resend_min_s = 0.2;
  double progress_every_s = 2.0;
  std::string masks_out;  // folder for dynamic masks (synthetic only); "" = none
};

struct CaptureSettings {
  PlayerOptions player;
  double max_association_difference_s = 0.02;  // colour/depth pairs further apart are not associated
  VerifyMode verify = VerifyMode::kHeader;
  double wait_timeout_s = 30.0;  // how long to wait for the --wait-for heartbeats
  // The scene played without --dataset; the configured name is relative to the configuration folder.
  std::string synthetic_config = "synthetic.yaml";

  // Command line only.
  std::string dataset;                // TUM-format folder; "" plays the synthetic scene
  std::string camera;                 // camera YAML; "" chooses by the folder
  std::string cameras_dir;            // where the camera is chosen from: <configuration folder>/cameras
  FrameSelection selection;           // --start, --end, --every
  std::string groundtruth_out;        // "" = not written
  std::vector<std::string> wait_for;  // process names; a name given twice waits for two such processes
  int loops = 1;                      // --loop: plays the source this many times as one stream (soak runs)
};

// bmp-capture's own options and --help epilog.
void addCaptureOptions(ArgParser& args);

// Reads every key of section (so Config::finish() accepts the file) and the options of addCaptureOptions.
// A value that breaks a rule throws ConfigError "<file>: key 'capture.speed' must be positive", or
// ArgError naming the option when the command line gave it. config_dir resolves the synthetic scene file
// and the cameras folder.
CaptureSettings readCaptureSettings(const Config& section, const ArgParser& args,
                                    const std::string& config_dir);

}  // namespace bmp::capture
