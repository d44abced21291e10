#pragma once
// A YOLO network in OpenCV DNN, loaded and checked at start-up: a missing, corrupt or wrongly-shaped model
// fails here with a ModelError naming the file, never at the first frame.
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

#include "detector/yolo_decode.hpp"

namespace bmp::detector {

class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ModelKind { kOnnx, kDarknet };

// Throws std::invalid_argument for anything but "onnx" or "darknet".
ModelKind parseModelKind(const std::string& text);
const char* toString(ModelKind kind);

struct ModelSpec {
  ModelKind kind = ModelKind::kOnnx;
  std::string path;         // .onnx, or darknet .weights; absolute (already resolved)
  std::string darknet_cfg;  // darknet .cfg; unused for ONNX
  std::string names;        // class names, one a line, in output order
  int input_size = 320;     // square network input, pixels
};

// One name a line; throws ModelError naming the file when it is missing or empty.
std::vector<std::string> loadClassNames(const std::string& path);

class YoloModel {
 public:
  // Loads the network and runs one dummy inference to check the output shape against input_size and the
  // number of class names. Throws ModelError.
  explicit YoloModel(const ModelSpec& spec);

  // square: input_size x input_size CV_8UC3 BGR (letterboxed). Returns N x (5 + classes) CV_32F rows.
  cv::Mat infer(const cv::Mat& square);
  // Decodes rows from infer() into candidate boxes in network-input pixels.
  std::vector<Candidate> decode(const cv::Mat& rows, float conf_threshold) const;

  const std::vector<std::string>& classNames() const { return names_; }
  int inputSize() const { return spec_.input_size; }
  const ModelSpec& spec() const { return spec_; }
  // File stem, e.g. "yolov5n_coco_320".
  std::string name() const;

 private:
  void checkOutputShape();
  ModelSpec spec_;
  std::vector<std::string> names_;
  cv::dnn::Net net_;
  std::vector<std::string> output_names_;
  std::vector<cv::Mat> outputs_;
  cv::Mat blob_;
};

}  // namespace bmp::detector
