#include "tracker/frame_log.hpp"

#include <cmath>
#include <iomanip>

namespace bmp::tracker {

const char* FrameLog::columns() {
  return "stamp\tseq\tstate\tkeypoints\ttracked\tpose_source\tfirst_inliers\tdynamic\texcluded\tmap_points\t"
         "keyframes\treference_kf\tnew_kf\tsince_last_ms\tframes_missed\tboxes\tgap_recheck\ttrack_ms\t"
         "extract_ms\tdynamic_ms\tlock_wait_ms\tposition_std_mm";
}

FrameLog::FrameLog(const std::string& path) : path_(path), out_(path) {
  if (!out_) throw FrameLogError(path + ": cannot write the frame log");
  out_ << "# bmp-tracker frame log: one line per frame (README, 'What comes out')\n# " << columns()
       << std::endl;
  if (!out_) throw FrameLogError(path + ": write failed");
}

void FrameLog::append(const TrackResult& r, const FrameLogContext& c) {
  out_ << std::fixed << std::setprecision(6) << r.stamp << '\t' << r.seq << '\t' << toString(r.state) << '\t'
       << r.num_keypoints << '\t' << r.num_tracked << '\t' << toString(r.pose_source) << '\t'
       << r.first_inliers << '\t' << r.num_dynamic << '\t' << r.num_excluded << '\t' << r.num_map_points
       << '\t' << r.num_keyframes << '\t' << r.reference_keyframe_id << '\t'
       << (r.new_keyframe ? r.new_keyframe->id : -1) << '\t' << std::setprecision(1)
       << r.since_last_s * 1000.0 << '\t' << c.frames_missed << '\t' << c.boxes << '\t'
       << toString(r.gap_recheck) << '\t' << std::setprecision(2) << r.processing_ms << '\t' << r.extract_ms
       << '\t' << r.dynamic_ms << '\t' << r.lock_wait_ms << '\t';
  // Not tracked, or a pose its inliers do not determine: no figure.
  if (std::isfinite(r.position_std_m))
    out_ << std::setprecision(1) << r.position_std_m * 1000.0;
  else
    out_ << '-';
  out_ << std::endl;
  if (!out_) throw FrameLogError(path_ + ": write failed");
}

}  // namespace bmp::tracker
