// Self-checking test runner for the C# binding (Mono): prints "N passed, N failed" and exits
// non-zero on any failure.
using System;
using System.Collections.Generic;
using Macrocon;

static class Tests
{
    static int passed, failed;

    static void Check(bool condition, string what)
    {
        if (!condition) throw new Exception("check failed: " + what);
    }

    static void Run(string name, Action test)
    {
        try { test(); passed++; Console.WriteLine("PASS " + name); }
        catch (Exception e) { failed++; Console.WriteLine("FAIL " + name + ": " + e); }
    }

    static (double[] P, uint[] T) Grid(int n)
    {
        var p = new double[3 * n * n];
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) { int v = j * n + i; p[3 * v] = i / (double)(n - 1); p[3 * v + 1] = j / (double)(n - 1); }
        var t = new List<uint>();
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i)
            {
                uint a = (uint)(j * n + i), b = a + 1, c = a + (uint)n + 1, d = a + (uint)n;
                t.AddRange(new[] { a, b, c, a, c, d });
            }
        return (p, t.ToArray());
    }

    static T Expect<T>(Action a) where T : Exception
    {
        try { a(); } catch (T e) { return e; }
        throw new Exception("expected " + typeof(T).Name);
    }

    static int Main()
    {
        Run("version and ABI", () =>
        {
            Library.CheckAbi();
            Check(Library.Version.Major == Library.AbiMajor, "major");
            Check(Library.StatusName(Status.NotADisk) == "MCON_ERROR_NOT_A_DISK", "status name");
        });
        Run("mesh from doubles and floats", () =>
        {
            var (p, t) = Grid(5);
            using (var ctx = new Context(2))
            using (var m = new Mesh(ctx, p, t)) Check(m.Counts.Vertices == 25 && m.Counts.Triangles == 32, "counts");
            var pf = Array.ConvertAll(p, x => (float)x);
            using (var ctx = new Context())
            using (var m = new Mesh(ctx, new ReadOnlySpan<float>(pf), t)) Check(m.Counts.Vertices == 25, "float counts");
        });
        Run("invalid mesh throws with status and message", () =>
        {
            var (p, t) = Grid(5);
            p[3 * 7 + 1] = double.NaN;
            using (var ctx = new Context())
            {
                var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, t));
                Check(e.Status == Status.NonFinite, "status");
                Check(e.Message.Contains("vertex 7"), "message names the vertex: " + e.Message);
                var (p2, t2) = Grid(5);
                t2[5] = 999;
                Check(Expect<InvalidMeshException>(() => new Mesh(ctx, p2, t2)).Status == Status.IndexOutOfRange, "range");
                Expect<ArgumentException>(() => new Mesh(ctx, new double[4], t2));
            }
        });
        Run("patch extraction", () =>
        {
            var (p, t) = Grid(41);
            using (var ctx = new Context())
            using (var m = new Mesh(ctx, p, t))
            using (var patch = Patch.Extract(m, 20 * 41 + 20, 0.3))
            {
                Check(patch.BoundaryLoops == 1 && patch.EulerCharacteristic == 1, "disk");
                Check(patch.ParamFlippedTriangles == 0, "no flips");
                Check(Math.Abs(patch.MaxGeodesicDistance - 1) < 0.1, "normalized");
                var pos = patch.Positions(); var uv = patch.Uv(); var tri = patch.Triangles();
                Check(pos.Length == 3 * patch.VertexCount && uv.Length == 2 * patch.VertexCount, "sizes");
                foreach (var idx in tri) Check(idx < patch.VertexCount, "index range");
                var (v0, v1, s) = patch.HostVertices();
                var c = patch.Center;
                for (int v = 0; v < patch.VertexCount; ++v)
                    for (int k = 0; k < 3; ++k)
                    {
                        double host = (1 - s[v]) * p[3 * v0[v] + k] + s[v] * p[3 * v1[v] + k];
                        Check(Math.Abs((host - c[k]) / patch.Radius - pos[3 * v + k]) < 1e-9, "host link");
                    }
                var d = patch.Descriptors(Descriptor.Curv9);
                Check(d.Length == 9 * patch.VertexCount, "descriptor size");
                foreach (var x in d) Check(Math.Abs(x) < 1e-6, "flat plane has zero curvature");
            }
        });
        Run("progress cancels and callback exceptions propagate", () =>
        {
            var (p, t) = Grid(31);
            using (var ctx = new Context())
            using (var m = new Mesh(ctx, p, t))
            {
                int calls = 0;
                Expect<CancelledException>(() => Patch.Extract(m, 15 * 31 + 15, 0.3, true, f => ++calls < 2));
                Check(calls == 2, "two calls");
                var e = Expect<InvalidOperationException>(() =>
                    Patch.Extract(m, 15 * 31 + 15, 0.3, true, f => throw new InvalidOperationException("boom")));
                Check(e.Message == "boom", "the callback's exception");
                Check(Expect<MacroconException>(() => Patch.Extract(m, 15 * 31 + 15, -1)).Status == Status.InvalidArgument, "radius");
            }
        });
        Run("heavy parallel work then shutdown", () =>
        {
            var (p, t) = Grid(81);
            using (var ctx = new Context())
            using (var m = new Mesh(ctx, p, t))
                for (int i = 0; i < 3; ++i)
                    using (var patch = Patch.Extract(m, 40 * 81 + 40, 0.2 + 0.1 * i)) patch.Descriptors(Descriptor.Curv9);
        });
        GC.Collect();
        GC.WaitForPendingFinalizers();
        Library.Shutdown();
        Console.WriteLine($"{passed} passed, {failed} failed");
        return failed == 0 ? 0 : 1;
    }
}
