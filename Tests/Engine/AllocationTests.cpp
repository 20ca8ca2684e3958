// The drum's audio-thread path allocates nothing, the energy ledger included: this test binary
// replaces the global operator new / delete and counts the allocations made on a thread while
// a thread_local flag is on, which the test sets around the calls it checks only.

#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

namespace
{
thread_local bool countingThisThread = false;
std::atomic<long> allocations { 0 };

void* allocate(std::size_t size)
{
    if (countingThisThread)
        allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size))
        return p;
    throw std::bad_alloc();
}

void* allocateAligned(std::size_t size, std::align_val_t alignment)
{
    if (countingThisThread)
        allocations.fetch_add(1, std::memory_order_relaxed);
    const auto a = static_cast<std::size_t>(alignment);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a))
        return p;
    throw std::bad_alloc();
}

struct CountAllocations
{
    CountAllocations() { countingThisThread = true; }
    ~CountAllocations() { countingThisThread = false; }
};
} // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept
{
    try { return allocate(size); } catch (...) { return nullptr; }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept
{
    try { return allocate(size); } catch (...) { return nullptr; }
}
void* operator new(std::size_t size, std::align_val_t a) { return allocateAligned(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return allocateAligned(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace snaresim;

TEST_CASE("the allocation counter sees allocations on the counted thread only", "[energy][realtime]")
{
    const long before = allocations.load();
    {
        CountAllocations counting;
        auto* p = new int(3);
        delete p;
    }
    CHECK(allocations.load() == before + 1);
    auto* q = new int(4); // not counted
    delete q;
    CHECK(allocations.load() == before + 1);
}

TEST_CASE("strikes, steps, the snares switch and reset allocate nothing, with the energy ledger kept", "[energy][realtime]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    EnergyLedger copy;
    double sum = 0.0;

    const long before = allocations.load();
    {
        CountAllocations counting;
        for (int n = 0; n < 3000; ++n)
        {
            if (n % 500 == 0)
                drum.playNote(38, 127);
            if (n == 1200)
                drum.playNote(33, 100); // snares off
            if (n == 1800)
                drum.playNote(34, 100); // snares on
            sum += drum.step();
            copy = drum.energy();       // as the renderer keeps every sample's ledger
            sum += copy.balance();
        }
        drum.reset();
        sum += drum.energy().total();
    }
    CHECK(allocations.load() == before);
    CHECK(std::isfinite(sum));
    CHECK(copy.size() == 5);
}

TEST_CASE("the drum in the air box steps without allocating", "[energy][realtime][airbox]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.cavity.model = AirModel::airbox;
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    double sum = 0.0;
    drum.step(); // the first step sizes nothing either, but keep the check on the steady state too
    const long before = allocations.load();
    {
        CountAllocations counting;
        for (int n = 0; n < 800; ++n)
        {
            if (n % 400 == 0)
                drum.playNote(38, 127);
            sum += drum.step();
            sum += drum.energy().balance() + drum.airMicPressure(0);
        }
    }
    CHECK(allocations.load() == before);
    CHECK(std::isfinite(sum));
    CHECK(drum.energy().size() == 6);
}
