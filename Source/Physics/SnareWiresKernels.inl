// The wires' free update (eq. 28), compiled once per vector target by PerVectorTarget.inl: no
// include guard, no includes.

// Every wire's interior in one pass over the flat array (it also visits the end nodes with the
// wrong stencil, corrected after), then the ends with their half-cell stencil (e, f).
void freeUpdate(int wires, int intervals, const double* __restrict u, const double* __restrict up, double* __restrict out, double a0,
                double a1, double b0, double b1, double e0, double e1, double f0, double f1)
{
    const int total = wires * (intervals + 1);
    for (int l = 1; l < total - 1; ++l)
        out[l] = a0 * u[l] + a1 * (u[l - 1] + u[l + 1]) + b0 * up[l] + b1 * (up[l - 1] + up[l + 1]);
    for (int i = 0; i < wires; ++i)
    {
        const int first = i * (intervals + 1), last = first + intervals;
        out[first] = e0 * u[first] + e1 * u[first + 1] + f0 * up[first] + f1 * up[first + 1];
        out[last] = e0 * u[last] + e1 * u[last - 1] + f0 * up[last] + f1 * up[last - 1];
    }
}
