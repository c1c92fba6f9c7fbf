// io: "did you mean" suggestions for misspelt names.
#pragma once

#include <string>
#include <vector>

namespace gpfd::io {

// Levenshtein distance between two strings.
std::size_t editDistance(const std::string& a, const std::string& b);
// The candidate closest to `name` when it is close enough to be a plausible typo (distance at
// most max(1, |name| / 3)); empty otherwise.
std::string closest(const std::string& name, const std::vector<std::string>& candidates);
// " (did you mean 'x'?)" or "".
std::string didYouMean(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace gpfd::io
