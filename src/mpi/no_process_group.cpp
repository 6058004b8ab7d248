// Built without MPI: every run is one process.
#include "launched_process_group.hpp"

namespace bssrdf {

void prepare_launched_process() {}

ProcessGroup* launched_process_group() { return nullptr; }

}  // namespace bssrdf
