#pragma once
// What the near field (NearFieldAir.h) is built from: its own settings, kept with the outside
// air's (OutsideAirSpec), the air and the shell (CavitySpec), the heads (MembraneSpec) and how
// far up the enclosed air's own modes reach (CavityModes.h; 0: none).

#include "CavitySpec.h"
#include "MembraneSpec.h"
#include "OutsideAirSpec.h"

namespace snaresim
{

struct NearFieldSpec
{
    OutsideAirSpec outside;
    CavitySpec cavity;
    MembraneSpec batter, carry;
    double cavityModesUpTo_Hz = 0.0; // above 0 the modes load the heads' inside, the near field the outside alone
};

} // namespace snaresim
