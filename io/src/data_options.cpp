#include <throng/io/data_options.h>

#include <optional>

namespace throng {
namespace {

// The fields both schemas share (import's and a tiling library's recorded crowd).
void fps_field(OptionBinder& b, ImportOptions& o) {
  std::optional<double> fps;  // absent: the rate the data states
  if (o.fps > 0) fps = o.fps;
  b.field({.key = "fps", .unit = "Hz", .range = Range::positive(), .flag = "--fps",
           .help = "frames per second of the frame numbers, where the data states no rate"},
          fps);
  o.fps = fps.value_or(0.0);
}
void credit_field(OptionBinder& b, ImportOptions& o) {
  b.field({.key = "credit", .flag = "--credit", .help = "credit stored in the provenance, after the data's own"}, o.credit);
}
void table_fields(OptionBinder& b, ImportOptions& o) {
  b.field({.key = "columns", .flag = "--columns", .help = "CSV column map time=t,id=pid,x=X,y=Y[,z=][,species=][,radius=]"},
          o.columns);
  b.choice({.key = "units", .flag = "--units", .help = "unit of the file's positions (default: the format's own)"}, o.units,
           {"", "m", "cm", "mm"});
}

}  // namespace

void describe_reading(OptionBinder& b, ImportOptions& o) {
  fps_field(b, o);
  credit_field(b, o);
  table_fields(b, o);
}

void describe(OptionBinder& b, ImportOptions& o) {
  fps_field(b, o);
  credit_field(b, o);
  b.field({.key = "species_from", .flag = "--species-from",
           .help = "none, groups.txt, a groups file, or a CSV column (default: the format's own)"},
          o.species_from);
  std::string obstacles = o.obstacles.string();
  b.field({.key = "obstacles", .flag = "--obstacles", .help = "obstacles from a map.xml or a crowd file instead of the data's"},
          obstacles);
  o.obstacles = obstacles;
  table_fields(b, o);
  b.field({.key = "radius", .unit = "m", .range = Range::non_negative(), .flag = "--radius", .help = "every agent's radius"},
          o.radius);
  b.field({.key = "wall_thickness", .unit = "m", .range = Range::non_negative(), .flag = "--wall-thickness",
           .help = "thickness of map.xml walls"},
          o.wall_thickness);
}

void describe(OptionBinder& b, PlotJob& job) {
  PlotOptions& o = job.picture;
  std::vector<std::int64_t> frames(o.frames.begin(), o.frames.end());
  b.field({.key = "frames", .flag = "--frames", .help = "frames where agents are drawn; negative counts from the end"}, frames);
  o.frames.assign(frames.begin(), frames.end());
  b.field({.key = "width", .unit = "px", .range = Range::closed(200, 20000), .flag = "--width", .help = "picture width"},
          o.width_px);
  b.field({.key = "title", .flag = "--title", .help = "title (default: the file name)"}, o.title);
  b.field({.key = "trajectories", .flag = "!--no-trajectories", .help = "draw the trajectories, not only the agents"},
          o.trajectories);
  b.field({.key = "obstacles", .flag = "!--no-obstacles", .help = "draw the obstacles"}, o.obstacles);
  b.field({.key = "min_agent_radius", .unit = "px", .range = Range::closed(0, 100), .flag = "--min-agent-radius",
           .help = "smallest agent disc radius"},
          o.min_agent_radius_px);
  b.choice({.key = "view", .flag = "--view", .help = "3-D crowds: top (x, y), front (x, z) or side (y, z)"}, job.view,
           {"top", "front", "side"});
  b.field({.key = "tiling", .flag = "!--no-tiling", .help = "a file written by throng tile is drawn as its patches"},
          job.tiling);
  b.section("preview", [&](OptionBinder& s) {
    PlotAnimation& a = job.picture.animation;
    s.field({.key = "fps", .unit = "Hz", .range = Range::closed(1, 60), .flag = "--preview-fps",
             .help = "animated preview (.gif, .mp4): frames per second"},
            a.fps);
    s.field({.key = "width", .unit = "px", .range = Range::closed(200, 4000), .flag = "--preview-width",
             .help = "animated preview width (rounded to even)"},
            a.width_px);
    s.field({.key = "max_duration", .unit = "s", .range = Range::positive(), .flag = "--max-duration",
             .help = "longest animated preview without --speed: longer crowds are sped up to fit"},
            a.max_duration_s);
    s.field({.key = "speed", .range = Range::positive(), .flag = "--speed",
             .help = "crowd seconds per preview second (default: real time, or sped up to fit max_duration)"},
            a.speed);
  });
}

void describe(OptionBinder& b, CheckTilingJob& job) {
  b.field({.key = "max_failures", .flag = "--max-failures", .help = "list at most this many failures (all are counted)"},
          job.max_failures);
}

}  // namespace throng
