#pragma once
// The room the drum is recorded in: its diffuse field at the microphones. A listener, as the
// microphones are: it stores none of the drum's energy and exerts no force.
//
// Sabine's diffuse field: a source heard at r metres in a room of volume V with reverberation
// time T60 brings a diffuse field of (r / r_c)^2 its direct sound's energy, the same at every
// point of the room, r_c = 0.057 sqrt(V / T60) (the critical distance, A = 0.161 V / T60 the
// absorption area, r_c^2 = A / 16 pi). Its time course is Schroeder's statistical one: dense,
// random, decaying exponentially. Here a feedback delay network makes it: eight delay lines
// (18-42 ms), a Householder matrix between them (lossless and dense), each line's loss a
// one-pole low-pass (Jot) set so that the field decays in 1.3 T60 at low frequencies and in
// 0.8 T60 at the highest (a small room rings longer low), the source fed in and the three
// microphones taken out along orthogonal rows of a Hadamard matrix (three diffuse fields that do
// not correlate). The source is the drum's free-field pressure at 1 m (Pa m), and the field's
// energy is 1 / r_c^2 of the source's: the network's response to an impulse is run through its
// first passes, where its echoes are still sparse, and the energy left in the lines then is
// counted as decaying at 60 dB per T60 (Tests/Engine/DiffuseRoomTests.cpp).
// Real-time safe after construction: setSpec and listen allocate nothing.

#include "RoomSpec.h"

#include <array>
#include <vector>

namespace snaresim
{

class DiffuseRoom
{
public:
    static constexpr int kLines = 8;
    static constexpr int kOutputs = 3; // the top, bottom and room microphones

    DiffuseRoom(const RoomSpec& spec, double sampleRate_Hz);

    // A new room (the lines keep what they hold). Allocates nothing; runs the network's first
    // passes once (about 4 x 2000 samples at 48 kHz).
    void setSpec(const RoomSpec& spec) noexcept;
    bool active() const noexcept { return on; }
    // The critical distance r_c (m), 0 without a room.
    double criticalDistance() const noexcept { return criticalDistance_m; }

    // One sample of the source (the drum's free-field pressure at 1 m, Pa m) in, the diffuse
    // field at the three microphones (Pa) out.
    std::array<double, kOutputs> listen(double source) noexcept;
    void clear() noexcept;

private:
    struct Network
    {
        std::array<std::vector<double>, kLines> line;
        std::array<int, kLines> pos {};
        std::array<double, kLines> loss {}; // the loss filters' states
        void clear() noexcept;
    };
    std::array<double, kOutputs> pass(Network& n, double in) const noexcept;

    double rate;
    bool on = false;
    double criticalDistance_m = 0.0;
    double inputGain = 0.0;
    std::array<int, kLines> length {};
    std::array<double, kLines> lossGain {}, lossPole {};
    Network live, trial; // trial: setSpec's run of the first passes
};

} // namespace snaresim
