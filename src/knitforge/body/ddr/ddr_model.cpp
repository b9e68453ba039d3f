#include "knitforge/body/ddr/ddr_model.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/core.h>

#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr const char* kFormat = "knitforge-ddr-1";

UNetOptions generator_options(const DdrModelInfo& info) { return {21, 2, info.size, info.width, 0.5}; }
UNetOptions refiner_options(const DdrModelInfo& info) { return {19, 1, info.size, info.width, 0.5}; }

template <typename Module>
void save_module(const Module& module, const std::filesystem::path& path) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  try {
    torch::save(module, tmp.string());
  } catch (const c10::Error& e) {
    std::filesystem::remove(tmp);
    throw IOError(fmt::format("{}: cannot write the network: {}", path.string(), e.what_without_backtrace()));
  }
  std::filesystem::rename(tmp, path);
}

template <typename Module>
void load_module(Module& module, const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    throw IOError(fmt::format("{}: missing; a model directory holds ddr.json, generator.pt and refiner.pt "
                              "(written by knitforge body ddr-train)",
                              path.string()));
  try {
    torch::load(module, path.string());
  } catch (const c10::Error& e) {
    throw IOError(fmt::format("{}: not a network of the size ddr.json describes, or not a LibTorch archive: {}",
                              path.string(), e.what_without_backtrace()));
  }
}

std::vector<float> run(UNetGenerator& net, const std::vector<float>& input, int channels, int size, uint64_t seed) {
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  if (input.size() != static_cast<size_t>(channels) * plane)
    throw InvalidInput(fmt::format("network input has {} values, not {} x {} x {}", input.size(), channels, size, size));
  torch::NoGradGuard no_grad;
  torch::manual_seed(seed);
  net->eval();
  const torch::Tensor x = torch::from_blob(const_cast<float*>(input.data()), {1, channels, size, size}).clone();
  const torch::Tensor y = net->forward(x).contiguous();
  return {y.data_ptr<float>(), y.data_ptr<float>() + y.numel()};
}

}  // namespace

DdrModel make_ddr_model(const DdrModelInfo& info, uint64_t seed) {
  torch::manual_seed(seed);
  DdrModel m;
  m.info = info;
  m.generator = UNetGenerator(generator_options(info));
  m.refiner = UNetGenerator(refiner_options(info));
  return m;
}

void save_ddr_model(const std::string& dir, const DdrModel& model) {
  const std::filesystem::path d(dir);
  std::error_code ec;
  std::filesystem::create_directories(d, ec);
  if (ec) throw IOError(fmt::format("{}: cannot create the model directory: {}", dir, ec.message()));
  save_module(model.generator, d / "generator.pt");
  save_module(model.refiner, d / "refiner.pt");
  const nlohmann::json j = {{"format", kFormat},
                            {"size", model.info.size},
                            {"width", model.info.width},
                            {"max_azimuth_deg", model.info.max_azimuth_deg},
                            {"training", model.info.training},
                            {"evaluation", model.info.evaluation}};
  const std::string text = j.dump(2);
  write_file_atomically((d / "ddr.json").string(), [&](std::ostream& out) { out << text << "\n"; });
}

DdrModel load_ddr_model(const std::string& dir) {
  const std::filesystem::path d(dir), json_path = d / "ddr.json";
  std::ifstream in(json_path);
  if (!in)
    throw IOError(fmt::format("{}: cannot read; a DDR model directory is written by knitforge body ddr-train",
                              json_path.string()));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw IOError(fmt::format("{}: not JSON: {}", json_path.string(), e.what()));
  }
  if (!j.is_object() || j.value("format", "") != kFormat)
    throw IOError(fmt::format("{}: \"format\" is not \"{}\"", json_path.string(), kFormat));
  DdrModelInfo info;
  try {
    info.size = j.at("size").get<int>();
    info.width = j.at("width").get<int>();
    info.max_azimuth_deg = j.at("max_azimuth_deg").get<double>();
    info.training = j.value("training", nlohmann::json::object());
    info.evaluation = j.value("evaluation", nlohmann::json::object());
  } catch (const nlohmann::json::exception& e) {
    throw IOError(fmt::format("{}: {}", json_path.string(), e.what()));
  }
  DdrModel m;
  try {
    m = make_ddr_model(info, 0);
  } catch (const InvalidInput& e) {
    throw IOError(fmt::format("{}: {}", json_path.string(), e.what()));
  }
  load_module(m.generator, d / "generator.pt");
  load_module(m.refiner, d / "refiner.pt");
  return m;
}

std::vector<float> predict_ddr(DdrModel& model, const std::vector<float>& input, uint64_t seed) {
  return run(model.generator, input, 21, model.info.size, seed);
}

std::vector<float> predict_view(DdrModel& model, const std::vector<float>& input, uint64_t seed) {
  return run(model.refiner, input, 19, model.info.size, seed);
}

}  // namespace knitforge
