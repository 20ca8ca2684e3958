#pragma once
// Counts the heap allocations a thread makes while it holds a CountAllocations: this header
// replaces the global operator new / delete (every form; the nothrow ones forward), so include
// it in exactly one file of a test binary. Other threads, and the counted thread outside the
// scope, are not counted.

#include <atomic>
#include <cstdlib>
#include <new>

namespace snaresim::test
{
inline thread_local bool countingThisThread = false;
inline std::atomic<long> countedAllocations { 0 };

struct CountAllocations
{
    CountAllocations() { countingThisThread = true; }
    ~CountAllocations() { countingThisThread = false; }
};

inline void* countedAllocate(std::size_t size)
{
    if (countingThisThread)
        countedAllocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size))
        return p;
    throw std::bad_alloc();
}

inline void* countedAllocateAligned(std::size_t size, std::align_val_t alignment)
{
    if (countingThisThread)
        countedAllocations.fetch_add(1, std::memory_order_relaxed);
    const auto a = static_cast<std::size_t>(alignment);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a))
        return p;
    throw std::bad_alloc();
}
} // namespace snaresim::test

void* operator new(std::size_t size) { return snaresim::test::countedAllocate(size); }
void* operator new[](std::size_t size) { return snaresim::test::countedAllocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept
{
    try
    {
        return snaresim::test::countedAllocate(size);
    }
    catch (...)
    {
        return nullptr;
    }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept
{
    try
    {
        return snaresim::test::countedAllocate(size);
    }
    catch (...)
    {
        return nullptr;
    }
}
void* operator new(std::size_t size, std::align_val_t a) { return snaresim::test::countedAllocateAligned(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return snaresim::test::countedAllocateAligned(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
