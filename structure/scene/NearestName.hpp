#pragma once
// "Did you mean ...?": the valid name nearest to a misspelt one. Used by every strict input reader (scene
// keys and choices, set and mesh names, the OpenFOAM adapter's options) so they suggest alike.
#include <string>
#include <vector>

namespace fsi {

/// Optimal string alignment distance (insertions, deletions, substitutions and swaps of two neighbours),
/// ignoring case: "shceme" is 1 from "scheme", "maptolerance" 0 from "mapTolerance".
int editDistance(const std::string& a, const std::string& b);

/// The candidate nearest to `word` (first one on ties); empty if there are none.
std::string nearestName(const std::string& word, const std::vector<std::string>& candidates);

/// The nearest candidate if it is close enough to be a likely misspelling (at most max(2, length/3) edits),
/// else "".
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace fsi
