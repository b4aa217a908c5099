// The crowd files a method command reads from its command line, in order, with what its output's provenance
// names (throng merge and throng stitch read two or more).
#pragma once

#include <throng/io/crowd_file.h>

#include <filesystem>
#include <string>
#include <vector>

namespace throng::cli {

struct InputCrowds {
  std::vector<CrowdFile> files;            ///< as read, in the order given
  Crowds crowds;                           ///< into `files` (a move of InputCrowds keeps them valid)
  std::vector<std::string> credits;        ///< the files' credits, each once
  std::vector<std::string> names;          ///< the files' paths, then the job's when there is one
};

/// Reads every input (read_crowd_file's errors, naming the file, propagate). `job_path` empty: no job.
[[nodiscard]] InputCrowds read_input_crowds(const std::vector<std::filesystem::path>& inputs,
                                            const std::filesystem::path& job_path);

}  // namespace throng::cli
