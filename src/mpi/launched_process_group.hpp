// The process group of an MPI launch, for the programs (bssrdf, generate_exact_table); in the
// bssrdf_mpi library, which opens the MPI plugin (libbssrdf-mpi.so) when CMake found MPI and returns null otherwise.
#pragma once

#include "bssrdf/process_group.hpp"

namespace bssrdf {

// The group this process was launched in (mpirun, srun: recognised from the launcher's environment),
// initialising MPI on first use; null when launched alone or built without MPI. Ranks other than 0
// have their standard output and error silenced (progress and errors are reported once, by rank 0),
// and rank 0 turns the launcher's SIGTERM, sent when another rank dies, into one line on stderr and
// exit status 3 (no output is written: rank 0 writes only after every rank delivered).
ProcessGroup* launched_process_group();

// Called first by the programs, before MPI is initialised: silences standard output and error of
// every rank but 0 of a launch (so that even errors in the command line are printed once), and lets
// rank 0 turn the launcher's SIGTERM into its one line from the start (a rank may die before MPI_Init).
void prepare_launched_process();

}  // namespace bssrdf
