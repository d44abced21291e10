#include "detector/yolo_model.hpp"

#include <filesystem>
#include <fstream>

namespace bmp::detector {

namespace {

void requireFile(const std::string& path, const char* what) {
  std::error_code ec;
  if (path.empty()) throw ModelError(std::string("no ") + what + " file configured");
  if (!std::filesystem::is_regular_file(path, ec)) throw ModelError(path + ": " + what + " file not found");
  if (std::filesystem::file_size(path, ec) == 0) throw ModelError(path + ": " + what + " file is empty");
}

std::string shapeOf(const cv::Mat& m) {
  std::string s;
  for (int i = 0; i < m.dims; ++i) s += (i ? "x" : "") + std::to_string(m.size[i]);
  return s;
}

// YOLOv5 predicts 3 anchors on each of the stride 8, 16 and 32 grids.
int yolov5Rows(int input_size) {
  int rows = 0;
  for (const int stride : {8, 16, 32}) rows += 3 * (input_size / stride) * (input_size / stride);
  return rows;
}

}  // namespace

ModelKind parseModelKind(const std::string& text) {
  if (text == "onnx") return ModelKind::kOnnx;
  if (text == "darknet") return ModelKind::kDarknet;
  throw std::invalid_argument("model kind must be 'onnx' or 'darknet', got '" + text + "'");
}

const char* toString(ModelKind kind) {
  return kind == ModelKind::kOnnx ? "onnx" : "darknet";
}

std::vector<std::string> loadClassNames(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ModelError(path + ": class names file not found");
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) names.push_back(line);
  }
  if (names.empty()) throw ModelError(path + ": no class names in file");
  return names;
}

YoloModel::YoloModel(const ModelSpec& spec) : spec_(spec) {
  names_ = loadClassNames(spec_.names);
  if (spec_.input_size < 32 || spec_.input_size % 32 != 0)
    throw ModelError(spec_.path + ": input size " + std::to_string(spec_.input_size) +
                     " must be a positive multiple of 32");
  requireFile(spec_.path, spec_.kind == ModelKind::kOnnx ? "ONNX model" : "darknet weights");
  if (spec_.kind == ModelKind::kDarknet) requireFile(spec_.darknet_cfg, "darknet cfg");
  try {
    net_ = spec_.kind == ModelKind::kOnnx ? cv::dnn::readNetFromONNX(spec_.path)
                                          : cv::dnn::readNetFromDarknet(spec_.darknet_cfg, spec_.path);
  } catch (const cv::Exception& e) {
    throw ModelError(spec_.path + ": cannot load " + toString(spec_.kind) + " model: " + e.what());
  }
  if (net_.empty()) throw ModelError(spec_.path + ": OpenCV DNN loaded an empty network");
  net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
  output_names_ = net_.getUnconnectedOutLayersNames();
  checkOutputShape();
}

void YoloModel::checkOutputShape() {
  const cv::Mat grey(spec_.input_size, spec_.input_size, CV_8UC3, cv::Scalar::all(114));
  cv::Mat rows;
  try {
    rows = infer(grey);
  } catch (const cv::Exception& e) {
    throw ModelError(spec_.path + ": test inference at " + std::to_string(spec_.input_size) + "x" +
                     std::to_string(spec_.input_size) +
                     " failed (wrong input size for this model?): " + e.what());
  }
  const int expected_cols = 5 + static_cast<int>(names_.size());
  if (rows.cols != expected_cols)
    throw ModelError(spec_.path + ": output rows have " + std::to_string(rows.cols) + " values, expected " +
                     std::to_string(expected_cols) + " (4 box + objectness + " +
                     std::to_string(names_.size()) + " classes of " + spec_.names + ")");
  if (spec_.kind == ModelKind::kOnnx && rows.rows != yolov5Rows(spec_.input_size))
    throw ModelError(spec_.path + ": output has " + std::to_string(rows.rows) + " rows, a YOLOv5 model at " +
                     std::to_string(spec_.input_size) + " gives " +
                     std::to_string(yolov5Rows(spec_.input_size)) +
                     " (is input_size the size the model was exported at?)");
}

cv::Mat YoloModel::infer(const cv::Mat& square) {
  // RGB scaled to [0, 1], NCHW: what both YOLOv5 and darknet expect.
  cv::dnn::blobFromImage(square, blob_, 1.0 / 255.0, cv::Size(), cv::Scalar(), /*swapRB=*/true,
                         /*crop=*/false);
  net_.setInput(blob_);
  outputs_.clear();
  net_.forward(outputs_, output_names_);
  if (spec_.kind == ModelKind::kOnnx) {
    if (outputs_.size() != 1 || outputs_[0].dims != 3 || outputs_[0].size[0] != 1)
      throw ModelError(spec_.path + ": expected one 1 x N x (5 + classes) output, got " +
                       std::to_string(outputs_.size()) + " output(s)" +
                       (outputs_.empty() ? std::string() : ", first " + shapeOf(outputs_[0])));
    return cv::Mat(outputs_[0].size[1], outputs_[0].size[2], CV_32F, outputs_[0].ptr<float>());
  }
  // Darknet: one N x (5 + classes) matrix per yolo layer.
  cv::Mat rows;
  for (const auto& out : outputs_) {
    if (out.dims != 2) throw ModelError(spec_.path + ": unexpected darknet output " + shapeOf(out));
    rows.push_back(out);
  }
  return rows;
}

std::vector<Candidate> YoloModel::decode(const cv::Mat& rows, float conf_threshold) const {
  return spec_.kind == ModelKind::kOnnx
             ? decodeRows(rows, ScoreLayout::kObjectnessTimesClass, 1.0f, conf_threshold)
             : decodeRows(rows, ScoreLayout::kClassIncludesObjectness, static_cast<float>(spec_.input_size),
                          conf_threshold);
}

std::string YoloModel::name() const {
  const std::string stem = std::filesystem::path(spec_.path).stem().string();
  return spec_.kind == ModelKind::kOnnx ? stem : stem + "_" + std::to_string(spec_.input_size);
}

}  // namespace bmp::detector
