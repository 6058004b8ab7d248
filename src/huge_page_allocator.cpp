#include "bssrdf/huge_page_allocator.hpp"

#include <sys/mman.h>

#include <cstdint>

namespace bssrdf {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kSmall = std::size_t{256} << 10;  // below: operator new (a huge page would be mostly idle)

std::size_t mapped_bytes(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

}  // namespace

void* allocate_huge_pages(std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  if (bytes >= kSmall && bytes <= (std::size_t{1} << 46)) {
    const std::size_t size = mapped_bytes(bytes);
    // Over-map by one huge page, then unmap the unaligned head and the tail beyond `size`.
    void* raw = mmap(nullptr, size + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(raw);
    const auto aligned = (start + kHugePage - 1) & ~(kHugePage - 1);
    if (aligned > start) munmap(raw, aligned - start);
    const std::size_t tail = start + size + kHugePage - (aligned + size);
    if (tail > 0) munmap(reinterpret_cast<void*>(aligned + size), tail);
    madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);  // a hint: without THP, 4 KB pages
    return reinterpret_cast<void*>(aligned);
  }
#endif
  return ::operator new(bytes);
}

void free_huge_pages(void* p, std::size_t bytes) noexcept {
  if (p == nullptr) return;
#ifdef MADV_HUGEPAGE
  if (bytes >= kSmall && bytes <= (std::size_t{1} << 46)) {
    munmap(p, mapped_bytes(bytes));
    return;
  }
#endif
  ::operator delete(p);
}

}  // namespace bssrdf
