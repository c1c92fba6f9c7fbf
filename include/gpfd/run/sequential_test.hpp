// run: the group-sequential test that can end a confirmation early (O'Brien & Fleming 1979, "A
// multiple testing procedure for clinical trials", Biometrics 35:549-556). The paired seeds are
// looked at `looks` times, after k/looks of them. At a look k < looks the trials end when the
// paired t-test's two-sided p-value is below the nominal level of the O'Brien-Fleming boundary
// z_k = C(looks) sqrt(looks / k), where C keeps the overall two-sided level at 0.05 (Jennison &
// Turnbull 2000, "Group Sequential Methods with Applications to Clinical Trials", Table 2.3);
// the last look always ends them. The boundary is strict early on (looks = 3: p < 0.00052 after
// a third of the seeds, p < 0.014 after two thirds), so only a clear difference ends the trials
// early, and it then has the sign the full set of seeds would almost surely give it.
#pragma once

#include "gpfd/run/statistics.hpp"

namespace gpfd::run {

inline constexpr int kMaxLooks = 5;  // The table's constants below go up to 5 looks.

// Seeds trained by the end of look `look` (1..looks): ceil(look * seeds / looks).
int seedsAtLook(int seeds, int look, int looks);

// The nominal two-sided level of look `look` of `looks`: 2 (1 - Phi(z_look)).
double nominalLevel(int look, int looks);

// Whether `difference` (the paired scores so far) ends the trials at look `look` of `looks`.
bool endsAtLook(const PairedComparison& difference, int look, int looks);

// Whether a confirmation's trials end at look `look` of `looks`, given the winner's paired
// comparisons with the original variables and (null: not scored) with the no-learning reference:
// at the last look; or where the winner clearly differs from the original variables
// (endsAtLook) and either lost to them or also clearly differs from no learning, so that more
// seeds would leave the decision as it is. Judging "better than no learning" at the last look's
// nominal level, nominalLevel(looks, looks), is then the group-sequential test of that question
// too: where the trials end early it has already passed the stricter level of that look.
bool confirmationEndsAtLook(const PairedComparison& vsOriginal,
                            const PairedComparison* vsNoLearning, int look, int looks);

}  // namespace gpfd::run
