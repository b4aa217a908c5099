#include "input_crowds.h"

namespace throng::cli {

InputCrowds read_input_crowds(const std::vector<std::filesystem::path>& inputs, const std::filesystem::path& job_path) {
  InputCrowds in;
  in.files.reserve(inputs.size());
  for (const auto& path : inputs) in.files.push_back(read_crowd_file(path));
  Provenance credits;
  for (const auto& f : in.files) {
    in.crowds.push_back(&f);
    credits.add_credits(f.provenance.credits);
  }
  in.credits = credits.credits;
  for (const auto& path : inputs) in.names.push_back(path.string());
  if (!job_path.empty()) in.names.push_back(job_path.string());
  return in;
}

}  // namespace throng::cli
