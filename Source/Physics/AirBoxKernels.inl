// The air box's layer loops (eq. 25, the cut links and the walls of eq. 51), compiled once per
// vector target by PerVectorTarget.inl: no include guard, no includes. AirBox.cpp is built
// without FMA contraction, so every target and every split between threads gives the same bits.

// v = a1 Psi^n + b1 Psi^{n-1} over one padded layer (its ghosts included: they mirror).
void layerV(double* __restrict v, const double* __restrict u, const double* __restrict up, long count, double a1, double b1)
{
    for (long i = 0; i < count; ++i)
        v[i] = a1 * u[i] + b1 * up[i];
}

// One layer of eq. (25), lossy: out = 2 u - up + L v, L the unscaled 7-point Laplacian over v of
// this layer (vc), the one below (vb) and the one above (va), i.e. out = a0 u + b0 up + (the six
// neighbours of v). Pointers at the padded layer's start. The loop runs over the layer's rows as
// one range, ghost columns included: no row ends to handle (those nodes are then fixed).
void layerLossy(double* __restrict out, const double* __restrict u, const double* __restrict up, const double* __restrict vc,
                const double* __restrict vb, const double* __restrict va, long first, long end, long sx, double a0, double b0)
{
    for (long m = first; m < end; ++m)
    {
        const double nb = (vc[m - 1] + vc[m + 1]) + (vc[m - sx] + vc[m + sx]) + (vb[m] + va[m]);
        out[m] = (a0 * u[m] + b0 * up[m]) + nb;
    }
}

// The same, computing on the way the v of one neighbouring layer (vn, from un and upn: the one
// below or the one above) while the other (vo) is given: the layer and that neighbour's v in one
// pass. The sum is the same either way round (vo + vn = vb + va exactly). vn's ghost columns
// come out as mirrors (their Psi are); its ghost rows are the caller's.
void layerLossyAhead(double* __restrict out, const double* __restrict u, const double* __restrict up, const double* __restrict vc,
                     const double* __restrict vo, double* __restrict vn, const double* __restrict un, const double* __restrict upn,
                     long first, long end, long sx, double a0, double b0, double a1, double b1)
{
    for (long m = first; m < end; ++m)
    {
        const double w = a1 * un[m] + b1 * upn[m];
        vn[m] = w;
        const double nb = (vc[m - 1] + vc[m + 1]) + (vc[m - sx] + vc[m + sx]) + (vo[m] + w);
        out[m] = (a0 * u[m] + b0 * up[m]) + nb;
    }
}

// The same without sigma_a (v = lambda^2 u): out = a0 u + a1 (6 neighbours of u) - up.
void layerLossless(double* __restrict out, const double* __restrict u, const double* __restrict up, long first, long end, long sx, long sxy,
                   double a0, double a1)
{
    for (long m = first; m < end; ++m)
    {
        const double nb = (u[m - 1] + u[m + 1]) + (u[m - sx] + u[m + sx]) + (u[m - sxy] + u[m + sxy]);
        out[m] = a0 * u[m] + a1 * nb - up[m];
    }
}

// The whole layer, in passes over it while it is cached: the cut links' terms taken back (from
// side[0..2], the v of the layers below, this, above (lossy); or, all nullptr, a1 (u_j - u_i)
// from u (lossless)), then the absorbing walls, then the ghost columns. A node's arithmetic is
// the same as in one pass row by row.
void fixLayer(double* __restrict out, const double* __restrict up, const double* const* side, const double* __restrict u, double a1, int nx,
              int ny, long sx, const LayerFixes& f)
{
    const AirCut* const cutEnd = f.cuts + f.rowStart[ny];
    if (side[1] != nullptr)
    {
        const double* const v1 = side[1];
        for (const AirCut* c = f.cuts + f.rowStart[0]; c != cutEnd; ++c)
            out[c->local] -= side[c->layer][c->local + c->shift] - v1[c->local];
    }
    else
        for (const AirCut* c = f.cuts + f.rowStart[0]; c != cutEnd; ++c)
            out[c->local] -= a1 * (u[c->local + c->delta] - u[c->local]);

    if (f.layerFaces >= 0)
    {
        // (1 + m lambda/2) Psi+ = [the update above] + (m lambda/2) Psi-
        for (int iy = 1; iy <= ny; ++iy)
        {
            const int my = f.layerFaces + (iy == 1) + (iy == ny);
            if (my == 0)
                continue;
            double* __restrict o = out + iy * sx + 1;
            const double* __restrict p = up + iy * sx + 1;
            const double g = f.gain[my], inv = f.inverse[my];
            for (int ix = 1; ix < nx - 1; ++ix)
                o[ix] = (o[ix] + g * p[ix]) * inv;
        }
        for (int iy = 1; iy <= ny; ++iy)
        {
            const int my = f.layerFaces + (iy == 1) + (iy == ny) + 1;
            const long r = iy * sx + 1;
            const double g = f.gain[my], inv = f.inverse[my];
            out[r] = (out[r] + g * up[r]) * inv;
            out[r + nx - 1] = (out[r + nx - 1] + g * up[r + nx - 1]) * inv;
        }
    }
    for (int iy = 1; iy <= ny; ++iy)
    {
        double* o = out + iy * sx + 1;
        o[-1] = o[0];
        o[nx] = o[nx - 1];
    }
}
