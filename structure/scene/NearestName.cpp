#include "structure/scene/NearestName.hpp"

#include <algorithm>
#include <cctype>

namespace fsi {

int editDistance(const std::string& a0, const std::string& b0) {
  std::string a = a0, b = b0;
  for (char& c : a) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (char& c : b) c = char(std::tolower(static_cast<unsigned char>(c)));
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = int(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = int(j);
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

namespace {
std::string nearest(const std::string& word, const std::vector<std::string>& candidates, int* distance) {
  std::string best;
  int bestDistance = -1;
  for (const std::string& c : candidates) {
    const int d = editDistance(word, c);
    if (bestDistance < 0 || d < bestDistance) bestDistance = d, best = c;
  }
  *distance = bestDistance;
  return best;
}
}  // namespace

std::string nearestName(const std::string& word, const std::vector<std::string>& candidates) {
  int d = 0;
  return nearest(word, candidates, &d);
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  int d = 0;
  const std::string best = nearest(word, candidates, &d);
  return d <= std::max<int>(2, int(word.size()) / 3) ? best : std::string();
}

}  // namespace fsi
