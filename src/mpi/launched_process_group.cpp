// The process group of an MPI launch, recognised from the launcher's environment. MPI itself sits in a
// plugin, libbssrdf-mpi.so (mpi_process_group.cpp), opened only when mpirun or srun started the
// process: linked into the programs, Open MPI's eight libraries cost every run 4.5 ms of its start
// (bssrdf --version: 22 -> 18 ms on the development machine), a fifth of a command's own time.
#include "launched_process_group.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// This process's rank as the launcher announces it (Open MPI's mpirun; PMIx or PMI as srun and
// MPICH's hydra set them), or -1 when no launcher started it.
int announced_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return -1;
}

int announced_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return 0;  // unknown (PMIx announces no size): assume several
}

void silence() {
  const int null = ::open("/dev/null", O_WRONLY);
  if (null < 0) return;
  ::dup2(null, STDOUT_FILENO);
  ::dup2(null, STDERR_FILENO);
  ::close(null);
}

extern "C" void on_terminate(int) {
  static const char message[] =
      "bssrdf: error: MPI run stopped by the launcher (a rank died or was killed); no output written\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(3);
}

#ifdef BSSRDF_MPI_PLUGIN
// The plugin beside an installed program (<prefix>/lib/bssrdf/), else the one this build made.
ProcessGroup* open_plugin() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  std::string looked, why;
  for (const std::string& path : {ec ? std::string() : (exe.parent_path() / BSSRDF_MPI_PLUGIN_INSTALLED).string(),
                                  std::string(BSSRDF_MPI_PLUGIN)}) {
    if (path.empty()) continue;
    looked += (looked.empty() ? "" : ", ") + path;
    if (!std::filesystem::exists(path, ec)) continue;
    if (void* plugin = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      using Factory = ProcessGroup* (*)();
      if (auto* make = reinterpret_cast<Factory>(::dlsym(plugin, "bssrdf_mpi_process_group"))) return make();
    }
    why = ::dlerror();
  }
  throw FileError("libbssrdf-mpi.so", 0,
                  "cannot load MPI support for this mpirun or srun launch: " +
                      (why.empty() ? "not found (looked at " + looked + ")" : why));
}
#endif

}  // namespace

void prepare_launched_process() {
  const int rank = announced_rank();
  if (rank > 0) silence();
  // From the start: a rank that dies before or during MPI_Init stops rank 0 there too.
  if (rank == 0 && announced_size() != 1) std::signal(SIGTERM, on_terminate);
}

ProcessGroup* launched_process_group() {
  if (announced_rank() < 0) return nullptr;
#ifdef BSSRDF_MPI_PLUGIN
  static ProcessGroup* const group = [] {
    ProcessGroup* g = open_plugin();  // MPI_Init; MPI_Finalize at exit
    if (g->rank() != 0)
      silence();
    else if (g->size() > 1)
      std::signal(SIGTERM, on_terminate);  // again, in case MPI_Init replaced it
    return g;
  }();
  return group;
#else
  return nullptr;  // built without MPI: every rank runs alone
#endif
}

}  // namespace bssrdf
