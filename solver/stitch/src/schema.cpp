#include <throng/edit/schema.h>
#include <throng/linalg/solver_schema.h>
#include <throng/stitch/jobs.h>
#include <throng/stitch/schema.h>
#include <throng/timewarp/schema.h>

#include <limits>

namespace throng::stitch {

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "blend_window", .unit = "s", .range = Range::non_negative(), .flag = "--blend-window",
           .help = "time from each joint over which formations blend, per side (0: the whole clips, within max_blend_vertices)"},
          o.blend_window);
  b.field({.key = "max_blend_vertices", .range = Range::closed(0, 1e12), .flag = "--max-blend-vertices",
           .help = "budget of the automatic window: agents × solved samples (0: none)"},
          o.max_blend_vertices);
  b.choice({.key = "matching", .flag = "--matching", .help = "how agents are matched across the joint"}, o.matching,
           {{"world", Matching::world}, {"centred", Matching::centred}});
  b.choice({.key = "alignment", .flag = "--alignment", .help = "how the next clip is moved onto the joint"}, o.alignment,
           {{"rigid", Alignment::rigid}, {"translation", Alignment::translation}, {"none", Alignment::none}});
  b.field({.key = "sample_step", .range = Range::closed(1, 1e9), .flag = "--sample-step", .help = "frames between graph samples"},
          o.sample_step);
  b.section("formation", [&](OptionBinder& f) {
    f.field({.key = "max_edge_length", .unit = "m", .range = Range::non_negative(),
             .help = "Delaunay edges longer than this are dropped (0: keep all)"},
            o.formation.max_edge_length);
  });
  edit::describe_weights(b, o.weights.alpha, o.weights.beta, o.weights.alpha_prime, o.weights.beta_prime);
  b.field({.key = "scale_compensation", .help = "step 2 (Eq. 8–10); false keeps step 1's result"}, o.weights.scale_compensation);
  b.section("features", [&](OptionBinder& f) { describe(f, o.features); });
  b.section("solver", [&](OptionBinder& s) { linalg::describe(s, o.solver); });
  b.section("guard", [&](OptionBinder& g) { timewarp::describe(g, o.guard); });
}

void describe(OptionBinder& b, MergeOptions& o) {
  b.choice({.key = "span", .flag = "--span",
            .help = "overlap: the frames every crowd shares; union: from the earliest start to the latest end"},
           o.span, {{"overlap", MergeSpan::overlap}, {"union", MergeSpan::union_of_spans}});
  b.choice({.key = "on_id_clash", .flag = "--on-id-clash", .help = "shift: a later crowd's ids move above the earlier ones'"},
           o.on_id_clash, {{"shift", IdClash::shift}, {"error", IdClash::error}});
  b.choice({.key = "join_by", .flag = "--join-by",
            .help = "id: agents with the same id in two crowds are one agent (clips of one recording); none: renumber"},
           o.join_by, {{"none", JoinBy::none}, {"id", JoinBy::id}});
  b.field({.key = "join_tolerance", .unit = "m", .range = Range::non_negative(), .flag = "--join-tolerance",
           .help = "joined by id: one agent's samples at one frame must be this close"},
          o.join_tolerance_m);
  b.field({.key = "time_tolerance", .unit = "s", .range = Range::non_negative(), .flag = "--time-tolerance",
           .help = "frame times closer than this are one frame"},
          o.time_tolerance_s);
  b.field({.key = "max_edge_length", .unit = "m", .range = Range::non_negative(), .flag = "--max-edge-length",
           .help = "stored formation edges longer than this are dropped (0: keep all)"},
          o.max_edge_length);
}

void describe(OptionBinder& b, SplitJob& job) {
  b.field({.key = "at_frame", .range = Range::non_negative(), .flag = "--at-frame",
           .help = "split by time at this frame (both parts hold it)"},
          job.at_frame);
  b.field({.key = "at_time", .unit = "s", .flag = "--at-time", .help = "split at the frame nearest this time"}, job.at_time);
  b.field({.key = "frames", .range = Range::non_negative(), .flag = "--frames", .help = "keep frames first..last", .length = 2},
          job.frames);
  b.field({.key = "times", .unit = "s", .flag = "--times", .help = "keep the frames nearest these times", .length = 2}, job.times);
  b.choice({.key = "keep", .flag = "--keep", .help = "the part of a split by time to keep"}, job.keep,
           {{"first", Part::first}, {"second", Part::second}});
  b.field({.key = "agents", .flag = "--agents", .help = "select these agent ids"}, job.agents);
  b.field({.key = "species", .range = Range::closed(0, std::numeric_limits<std::int32_t>::max()), .flag = "--species",
           .help = "select every agent of these species"},
          job.species);
  b.choice({.key = "keep_agents", .flag = "--keep-agents", .help = "the part of a split by agents to keep"}, job.keep_agents,
           {{"selected", AgentPart::selected}, {"rest", AgentPart::rest}});
  b.field({.key = "present_throughout", .flag = "--present-throughout",
           .help = "keep only agents present at every frame of the part"},
          job.present_throughout);
}

void describe(OptionBinder& b, TransformJob& job) {
  b.field({.key = "rotate", .unit = "deg", .flag = "--rotate", .help = "counter-clockwise, about the pivot"}, job.rotate);
  b.field({.key = "pivot", .unit = "m", .flag = "--pivot", .help = "the rotation's fixed point (default: the first frame's centroid)",
           .length = 2},
          job.pivot);
  b.field({.key = "translate", .unit = "m", .flag = "--translate", .help = "moves the clip after the rotation", .length = 2},
          job.translate);
  b.field({.key = "place_at", .unit = "m", .flag = "--place-at",
           .help = "moves the first frame's centroid here (instead of translate)", .length = 2},
          job.place_at);
  b.field({.key = "time_scale", .range = Range::positive(), .flag = "--time-scale", .help = "durations multiply by this (2: half as fast)"},
          job.time_scale);
  b.field({.key = "time_shift", .unit = "s", .flag = "--time-shift", .help = "added to every time"}, job.time_shift);
  b.field({.key = "start_time", .unit = "s", .flag = "--start-time", .help = "the first frame's new time (instead of time_shift)"},
          job.start_time);
  b.field({.key = "frame_rate", .unit = "Hz", .range = Range::non_negative(), .flag = "--frame-rate",
           .help = "resample at this many frames per second (0: keep the frames)"},
          job.frame_rate);
  b.field({.key = "id_offset", .flag = "--id-offset", .help = "added to every agent id"}, job.id_offset);
  b.field({.key = "species", .range = Range::closed(0, std::numeric_limits<std::int32_t>::max()), .flag = "--species",
           .help = "every agent's species becomes this"},
          job.species);
}

}  // namespace throng::stitch
