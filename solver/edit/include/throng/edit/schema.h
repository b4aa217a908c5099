// The schema of edit::Options (throng/core/schema.h), and the pieces the stitch job shares with it: the feature
// options and the weights of Eq. 4 and 9. The defaults are the initialisers in edit.h, features.h and
// feature_deformation.h. validate() checks these ranges.
#pragma once

#include <throng/core/schema.h>
#include <throng/edit/edit.h>
#include <throng/edit/feature_deformation.h>
#include <throng/graph/features.h>

namespace throng::edit {

/// `clip`, `formation` (its max_edge_length; edits are job data, io/edge_edits.h), `weights`,
/// `scale_compensation`, `features`, `solver`, `local`.
void describe(OptionBinder& b, Options& o);

/// The `weights:` block: α, β of Eq. 4 and α′, β′ of Eq. 9.
void describe_weights(OptionBinder& b, double& alpha, double& beta, double& alpha_prime, double& beta_prime);

}  // namespace throng::edit

namespace throng {

/// The `features:` block (throng/graph/features.h).
void describe(OptionBinder& b, FeatureOptions& o);

}  // namespace throng
