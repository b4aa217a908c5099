#include <throng/edit/schema.h>
#include <throng/linalg/solver_schema.h>

#include <limits>

namespace throng {

void describe(OptionBinder& b, FeatureOptions& o) {
  b.field({.key = "min_length", .unit = "m", .range = Range::positive(), .help = "feature arm lengths below this count as this"},
          o.min_length);
  b.field({.key = "degenerate_ratio", .range = {0.0, 1.0, false, true},
           .help = "a feature is degenerate when |w − u| ≤ ratio · (|v − u| + |v − w|)"},
          o.degenerate_ratio);
}

}  // namespace throng

namespace throng::edit {

void describe_weights(OptionBinder& b, double& alpha, double& beta, double& alpha_prime, double& beta_prime) {
  b.section("weights", [&](OptionBinder& w) {
    w.field({.key = "alpha", .range = Range::non_negative(), .help = "α: the temporal term in step 1 (Eq. 4)"}, alpha);
    w.field({.key = "beta", .range = Range::non_negative(), .help = "β: the spatiotemporal term in step 1 (Eq. 4)"}, beta);
    w.field({.key = "alpha_prime", .range = Range::non_negative(), .help = "α′: the temporal term in step 2 (Eq. 9)"},
            alpha_prime);
    w.field({.key = "beta_prime", .range = Range::non_negative(), .help = "β′: the spatiotemporal term in step 2 (Eq. 9)"},
            beta_prime);
  });
}

void describe(OptionBinder& b, Options& o) {
  b.section("clip", [&](OptionBinder& c) {
    c.field({.key = "first_frame", .range = Range::non_negative(), .help = "the clip's first input frame"}, o.clip.first_frame);
    constexpr std::size_t open_end = std::numeric_limits<std::size_t>::max();
    std::int64_t last = o.clip.last_frame == open_end ? -1 : static_cast<std::int64_t>(o.clip.last_frame);
    c.field({.key = "last_frame", .range = Range::non_negative(), .help = "the clip's last input frame", .value = "a frame index"},
            last, {{"end", -1}});
    o.clip.last_frame = last < 0 ? open_end : static_cast<std::size_t>(last);
    std::optional<std::vector<std::int64_t>> agents;  // absent: every agent present over the whole clip
    if (!o.clip.agents.empty()) agents = o.clip.agents;
    c.field({.key = "agents", .help = "ids of the agents to edit (default: every agent present over the whole clip)"}, agents);
    o.clip.agents = agents.value_or(std::vector<std::int64_t>{});
    c.field({.key = "sample_step", .range = Range::closed(1, 1e9), .help = "sample every so many frames"}, o.clip.sample_step);
  });
  b.section("formation", [&](OptionBinder& f) {
    f.field({.key = "max_edge_length", .unit = "m", .range = Range::non_negative(),
             .help = "Delaunay edges longer than this are dropped (0: keep all)"},
            o.formation.max_edge_length);
  });
  describe_weights(b, o.alpha, o.beta, o.alpha_prime, o.beta_prime);
  b.field({.key = "scale_compensation", .help = "step 2 (Eq. 8–10); false keeps step 1's result"}, o.scale_compensation);
  b.section("features", [&](OptionBinder& f) { describe(f, o.features); });
  b.section("solver", [&](OptionBinder& s) {
    linalg::describe(s, o.solver);
    linalg::describe_method(s, o.solver);
  });
  b.section("local", [&](OptionBinder& l) {
    std::int64_t parts = o.local.parts;
    l.field({.key = "parts", .range = Range::closed(0, 1e9), .flag = "--local-parts",
             .help = "local edit: solve only the METIS parts the edit reaches (0: global; auto: parts of vertices_per_part)",
             .value = "a part count"},
            parts, {{"auto", LocalOptions::by_size}});
    o.local.parts = static_cast<int>(parts);
    l.field({.key = "vertices_per_part", .range = Range::closed(1, 1e9), .help = "part size for parts: auto"},
            o.local.vertices_per_part);
    l.field({.key = "halo", .range = Range::closed(-1, 1e9), .flag = "--halo",
             .help = "parts within this many hops of the reached ones are solved too (-1: every connected part)"},
            o.local.halo);
    l.field({.key = "seed", .range = Range::closed(0, 2147483646), .help = "METIS seed: same seed, same parts"}, o.local.seed);
    l.field({.key = "max_cached_regions", .range = Range::closed(1, 1e6), .help = "factorised regions kept for later drags"},
            o.local.max_cached_regions);
  });
}

}  // namespace throng::edit
