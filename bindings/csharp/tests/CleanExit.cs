// A Mono process that runs heavy parallel SDK work (a library's build_retrieval, a map compute)
// and exits without disposing anything: the binding's exit hook (AppDomain.ProcessExit) must
// release the handles and call mcon_shutdown, and the process must exit with status 0
// (docs/design.md §5: without the shutdown path Mono segfaulted at exit after tbb::parallel_for).
// Prints "done" and then, from a ProcessExit handler subscribed after the binding's own, the
// status of the binding's mcon_shutdown call: "exit_status Ok".
using System;
using Macrocon;

static class CleanExit
{
    // Static roots: nothing here is collected before exit, so only the exit hook can release it.
    static Context ctx;
    static Mesh mesh;
    static Patch[] patches;
    static ConstraintLibrary lib;
    static Map map;

    static int Main(string[] args)
    {
        bool withMap = args.Length > 0 && args[0] == "map";
        const int n = 61;
        var p = new double[3 * n * n];
        var t = new uint[6 * (n - 1) * (n - 1)];
        for (int j = 0, k = 0; j < n; ++j)
            for (int i = 0; i < n; ++i, ++k)
            {
                double x = i / (double)(n - 1), y = j / (double)(n - 1);
                p[3 * k] = x; p[3 * k + 1] = y;
                p[3 * k + 2] = 0.15 * Math.Sin(5 * x + 1) * Math.Cos(3 * y) + 0.1 * x * x * y + 0.05 * Math.Sin(9 * x * y);
            }
        for (int j = 0, f = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i)
            {
                uint a = (uint)(j * n + i), b = a + 1, c = a + n + 1, d = a + n;
                t[f++] = a; t[f++] = b; t[f++] = c; t[f++] = a; t[f++] = c; t[f++] = d;
            }
        ctx = new Context();
        // Subscribed after the binding's hook (installed with the first handle): runs after it.
        AppDomain.CurrentDomain.ProcessExit += (s, e) => Console.WriteLine("exit_status " + Library.ExitStatus);
        mesh = new Mesh(ctx, p, t);
        patches = new[] { Patch.Extract(mesh, 20 * n + 20, 0.2), Patch.Extract(mesh, 30 * n + 40, 0.2), Patch.Extract(mesh, 40 * n + 25, 0.2) };
        lib = new ConstraintLibrary(ctx);
        foreach (var q in patches) lib.AddEntry(q, new EntryDesc { Name = "x" });
        lib.BuildRetrieval(new RetrievalSettings { VocabularySize = 16 });  // parallel k-means and histograms
        if (withMap) map = Map.Compute(patches[0], patches[1], new MapSettings { AlignmentSamples = 2000, MaxIterations = 30 });
        Console.WriteLine("done " + lib.Query(patches[0], 2).Count + (map != null ? " map" : ""));
        return 0;
    }
}
