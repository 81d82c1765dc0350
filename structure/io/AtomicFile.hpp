#pragma once
// Replacing a file so that it always holds either its previous or its new complete content, also after a
// crash of the program or of the machine: the new content goes to a temporary file next to it, which is
// synced to disk and only then renamed over the file. Used by every file a reader may open while a run goes
// on or after it stopped: restart states (StateFile) and the XDMF index of a results series (ResultsWriter).

#include <filesystem>
#include <functional>

namespace fsi::structure {

/// `write(tmp)` creates and fills the temporary file `file` + ".tmp" (and throws on failure); it is then
/// synced and renamed to `file`, and the directory synced so the rename itself is on disk. On any failure the
/// temporary file is removed and a std::runtime_error naming the file, prefixed with `who`, is thrown
/// (`write`'s own exception passes through unchanged).
void replaceFileAtomically(const std::filesystem::path& file, const char* who,
                           const std::function<void(const std::filesystem::path& tmp)>& write);

}  // namespace fsi::structure
