#pragma once
// Coupling between the heads and the outside air's channels (OutsideAir.h): the channels'
// pressures at time n act on the heads in their free updates (explicit), a uniform part from the
// monopole and dipole and a first-moment part p_x x + p_y y from the tilt channels; once
// the contacts have moved the heads, their volumes and first moments give q^{n+1}. It stores no
// energy and removes none: the pressures' work on the heads over a step is exactly what the
// channels' energy and losses take (OutsideAir.h).

#include "Membrane.h"
#include "OutsideAir.h"

namespace snaresim
{

// A pressure p0 + px x + py y on a head (Pa, Pa/m), pushing up.
struct HeadPressure
{
    double p0 = 0.0, px = 0.0, py = 0.0;
};

class OutsideAirCoupling
{
public:
    // The heads keep their first moments for it (Membrane::keepMoments): no pass of its own.
    OutsideAirCoupling(Membrane& batterHead, Membrane& carryHead, OutsideAir& outsideAir)
        : batter(batterHead), carry(carryHead), air(outsideAir)
    {
        if (air.active())
        {
            batter.keepMoments();
            carry.keepMoments();
        }
    }

    // The pressure on each head at time n (q_m = V_b - V_c, q_d = V_b + V_c, q_s = X_b + X_c, q_t = X_b - X_c).
    HeadPressure onBatter() const
    {
        return { air.pressure(OutsideAir::dipole) + air.pressure(OutsideAir::monopole),
                 air.pressure(OutsideAir::tiltSumX) + air.pressure(OutsideAir::tiltDiffX),
                 air.pressure(OutsideAir::tiltSumY) + air.pressure(OutsideAir::tiltDiffY) };
    }
    HeadPressure onCarry() const
    {
        return { air.pressure(OutsideAir::dipole) - air.pressure(OutsideAir::monopole),
                 air.pressure(OutsideAir::tiltSumX) - air.pressure(OutsideAir::tiltDiffX),
                 air.pressure(OutsideAir::tiltSumY) - air.pressure(OutsideAir::tiltDiffY) };
    }

    // After every force on the heads is in: q^{n+1}.
    void step()
    {
        const double vb = batter.sweptVolumeNext(), vc = carry.sweptVolumeNext();
        const auto tb = batter.tiltNext(), tc = carry.tiltNext();
        air.setCoordinatesNext({ vb - vc, vb + vc, tb[0] + tc[0], tb[1] + tc[1], tb[0] - tc[0], tb[1] - tc[1] });
    }

    double energy() const { return 0.0; }
    double stepLoss() const { return 0.0; }

private:
    Membrane& batter;
    Membrane& carry;
    OutsideAir& air;
};

} // namespace snaresim
