#pragma once
// The room the drum is heard in (DiffuseRoom.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

namespace snaresim
{

struct RoomSpec
{
    double reverberationTime_s = 0.0; // T60 at middle frequencies (from the schema); 0: no room, the free field
    double volume_m3 = 60.0;          // the room's volume (from the schema)
    bool operator==(const RoomSpec&) const = default;
};

} // namespace snaresim
