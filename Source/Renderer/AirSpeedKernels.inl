// The bare stencil the air box is timed against (AirSpeed.h), compiled once per vector target
// by PerVectorTarget.inl: no include guard, no includes.

// The bare loop: out = a0 u + a1 (6 neighbours) - up over every node of a padded nx x ny x nz grid.
template <class T>
void bareLoop(T* __restrict out, const T* __restrict u, const T* __restrict up, int nx, int ny, int nz, T a0, T a1)
{
    const long sx = nx + 2, sxy = sx * (ny + 2);
    for (int iz = 1; iz <= nz; ++iz)
        for (int iy = 1; iy <= ny; ++iy)
        {
            const long r = iz * sxy + iy * sx + 1;
            const T* v = u + r;
            const T* vp = up + r;
            T* o = out + r;
            for (int m = 0; m < nx; ++m)
            {
                const T nb = (v[m - 1] + v[m + 1]) + (v[m - sx] + v[m + sx]) + (v[m - sxy] + v[m + sxy]);
                o[m] = a0 * v[m] + a1 * nb - vp[m];
            }
        }
}
