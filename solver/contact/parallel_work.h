#pragma once

namespace fibrecheck {

/// Loops over contacts (or load points) run on several threads only above this many. Each
/// parallel region wakes the other threads and waits for them: on a shared machine, where a
/// waiting thread sleeps instead of spinning, a wake-up costs tens of microseconds, more than a
/// pass over a few thousand contacts. The iterations on a working set of a tow stay below it; the
/// passes over every candidate (revisions, detection) and the large working sets use the cores.
inline constexpr int kParallelContacts = 32768;

}  // namespace fibrecheck
