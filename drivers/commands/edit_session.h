// `throng edit CROWD.h5 --job BASE.yaml --session`: a long-lived edit for a DCC plugin's drag loop
// (solver/edit session.h; the protocol, for plugin authors, is docs/commands/edit.md, "Session").
//
// The crowd and the job (file, flags, --set: its options, clip_only and guard) are read once. Then each line of
// `in` is one JSON object, a request:
//   {"id": 7, "drags": [{"agents": [1], "offset": [2, 0]}], "pins": [...], "constraints": [...], "output": "a.h5"}
// pins, drags and constraints are the job file's keys, read by the job's own reader (io/edit edit_job.h) with
// the job's options, so every request kind a job knows works here; they replace the job's request as a whole (a
// key left out means none). "output" (optional) writes the edited crowd there, atomically, exactly as
// `throng edit CROWD.h5 --job <the job with this request> -o <output>` would (only the provenance's command line
// differs). "id" (any JSON value) is echoed. {"command": "quit"} (or the end of `in`) ends the session;
// {"command": "prepare", "drags": ...} makes the editor ready for those handles without answering an edit
// (edit::Session::prepare), as the session does at its start for the job's own pins and drags.
// "answer": "preview" (default "full") answers with the solve alone (edit::Session::preview: the same editor and
// solve as a full answer, none of the resampling, putting back, guard and crowd file after it): the solve's report
// fields and the largest sample displacement; a preview with "output" is refused (exit 2). "samples_output" (either
// answer) writes the edited sample positions there, atomically, in the raw layout write_samples() gives (the
// samples a full answer resampled, bit for bit the preview's).
// Each request gets one JSON line on `out`, flushed:
//   {"id": 7, "ok": true, "editor": "reused", "bit_identical": true, "edit_s": ..., "write_s": ..., "answer_s": ...,
//    "warnings": [...], "report": {the one-shot report's fields}}
//   {"id": 7, "ok": false, "exit_code": 2, "error": "request line 3:1:24 (drags[0].agents): ..."}
//   {"id": 7, "ok": true, "answer": "preview", "editor": "reused", ..., "report": {"samples": ..., "solve_s": ...}}
// A bad request (not JSON, an unknown key, an entry that does not fit the crowd, a singular system, an output that
// cannot be written) is answered with the message and the exit code a one-shot edit would give, writes no file
// and does not end the session. Logs and warnings go to stderr only.
#pragma once

#include "../context.h"

#include <throng/io/config.h>

#include <filesystem>
#include <iosfwd>

namespace throng::cli {

/// Runs a session over `crowd` with the base job `job` (read from `job_path`, flags and --set applied) until the
/// end of `in` or a quit command; returns normally then (exit 0). The crowd's and the job's own errors (before any
/// line is read) throw as a one-shot edit's do; a request's errors are answered on `out`.
void run_edit_session(Context& context, const std::filesystem::path& crowd, const std::filesystem::path& job_path,
                      const ConfigNode& job, std::istream& in, std::ostream& out);

}  // namespace throng::cli
