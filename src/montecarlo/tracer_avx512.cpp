// The photon tracer compiled for AVX-512: all eight lanes in one 512-bit register. Its own
// translation unit because GCC decides the type of a vector comparison where a function is compiled,
// before inlining: compiled for an older instruction set (as the tracer's steps are in tracer.cpp,
// which serves every x86-64), a comparison of eight doubles becomes eight scalar ones even when
// inlined into an AVX-512 function; under the pragma below it is one instruction with a mask.
// The operations are those of the other fused kernels, lane by lane: bitwise identical results.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "bssrdf/check.hpp"
#include "bssrdf/fresnel.hpp"
#include "fastmath.hpp"
#include "tracer.hpp"

#if defined(__x86_64__) || defined(__i386__)
// Every header lane_tracer.hpp includes is above, so the pragma reaches only its functions (internal
// linkage). Clang lowers vector code where it is inlined and needs no pragma.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC target("avx2,fma,avx512f,avx512vl,avx512dq")
#endif
#include "lane_tracer.hpp"

namespace bssrdf::mc {

template <bool kAnalog>
__attribute__((target("avx2,fma,avx512f,avx512vl,avx512dq"))) void trace_avx512(
    const ChannelGeometry& geo, const TraceSettings& settings, Rng& rng, std::uint64_t photons, BatchTally& tally) {
  trace_lanes<kAnalog, Avx512>(geo, settings, rng, photons, tally);
}
template void trace_avx512<true>(const ChannelGeometry&, const TraceSettings&, Rng&, std::uint64_t, BatchTally&);
template void trace_avx512<false>(const ChannelGeometry&, const TraceSettings&, Rng&, std::uint64_t, BatchTally&);

}  // namespace bssrdf::mc
#endif
