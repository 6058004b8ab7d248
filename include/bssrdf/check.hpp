// Internal invariants, in pbrt's habit (CHECK / DCHECK): an assumption of the library's own code,
// never the user's input (bad input is an InvalidInput naming the field, the value and the range).
// BSSRDF_CHECK is always on and costs a comparison; BSSRDF_DCHECK is for hot paths (the Monte Carlo
// lanes, per-sample loops) and is compiled only without NDEBUG (Debug and sanitizer builds).
// A failed check throws InternalError naming the condition, file and line: the command line prints
// it as a bug (exit status 1), a library user can catch it, and nothing aborts mid-write.
//
//   BSSRDF_CHECK(lo < hi);                       // a bracket the search above guarantees
//   BSSRDF_DCHECK(weight >= 0);                  // per photon step: Debug builds only
#pragma once

#include <stdexcept>
#include <string>

namespace bssrdf {

class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace bssrdf

#define BSSRDF_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::bssrdf::check_failed(#condition, __FILE__, __LINE__))

#ifdef NDEBUG
#define BSSRDF_DCHECK(condition) static_cast<void>(0)
#else
#define BSSRDF_DCHECK(condition) BSSRDF_CHECK(condition)
#endif
