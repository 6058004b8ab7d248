// Built without MPI: every run is one process.
#include "launched_process_group.hpp"

namespace bssrdf {

void silence_other_ranks() {}

ProcessGroup* launched_process_group() { return nullptr; }

}  // namespace bssrdf
