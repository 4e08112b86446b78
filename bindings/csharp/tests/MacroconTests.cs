// Self-checking test runner for the C# binding (Mono): prints "N passed, N failed" and exits
// non-zero on any failure.
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using Macrocon;

static class Tests
{
    static int passed, failed;
    const uint Native_InvalidIndex = 0xFFFFFFFFu;

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

    // An asymmetric height field over the grid (curvature for descriptors, no mirror symmetry).
    static (double[] P, uint[] T) Bumpy(int n)
    {
        var r1 = Grid(n); var p = r1.Item1; var t = r1.Item2;
        for (int v = 0; v < n * n; ++v)
        {
            double x = p[3 * v], y = p[3 * v + 1];
            p[3 * v + 2] = 0.15 * Math.Sin(5 * x + 1) * Math.Cos(3 * y) + 0.1 * x * x * y + 0.05 * Math.Sin(9 * x * y);
        }
        return (p, t);
    }

    static readonly (int I, int J)[] Centers = { (12, 12), (20, 20), (28, 14), (14, 27), (26, 26) };

    static SurfacePoint Third(uint face) => new SurfacePoint(face, 1.0 / 3, 1.0 / 3, 1.0 / 3);

    static EntryDesc Example(Patch patch, int k)
    {
        int n = patch.VertexCount, m = patch.TriangleCount;
        var pos = patch.Positions();
        var weights = new double[2 * n]; var colour = new double[3 * n]; var labels = new int[n];
        for (int v = 0; v < n; ++v)
        {
            weights[2 * v] = pos[3 * v] * pos[3 * v]; weights[2 * v + 1] = 1 - pos[3 * v + 1];
            for (int c = 0; c < 3; ++c) colour[3 * v + c] = Math.Abs(pos[3 * v + c]);
            labels[v] = v % 3;
        }
        return new EntryDesc
        {
            Name = "entry " + k, ClassLabel = "bump", Author = "mono", Licence = "CC0-1.0", Tags = new[] { "test", "k" + k },
            Polylines = new[]
            {
                new Polyline { Points = new[] { Third(0), Third((uint)m / 2), Third((uint)m - 1) } },
                new Polyline { Kind = PolylineKind.Feature, Closed = true,
                               Points = new[] { Third(1), Third(2), Third(3), Third(4) } },
            },
            Singularities = new[] { new Singularity(new SurfacePoint(5, 0.6, 0.2, 0.2), 1), new Singularity(Third((uint)m / 3), -1) },
            Fields = new[]
            {
                new Field { Name = "weights", Kind = FieldKind.Scalar, Dimension = 2, Values = weights },
                new Field { Name = "colour", Kind = FieldKind.Vector3, Dimension = 3, Values = colour },
                new Field { Name = "part", Kind = FieldKind.IntegerLabel, Dimension = 1, Labels = labels },
                new Field { Name = "uv", Kind = FieldKind.Uv, Dimension = 2, Values = patch.Uv() },
            },
        };
    }

    static Patch[] Patches(Mesh m)
    {
        var ps = new Patch[Centers.Length];
        for (int k = 0; k < ps.Length; ++k) ps[k] = Patch.Extract(m, (uint)(Centers[k].J * 41 + Centers[k].I), 0.22);
        return ps;
    }

    static ConstraintLibrary Filled(Context ctx, Patch[] ps)
    {
        var lib = new ConstraintLibrary(ctx);
        for (int k = 0; k < ps.Length; ++k) lib.AddEntry(ps[k], Example(ps[k], k));
        return lib;
    }

    static void Near(double a, double b, double tol, string what)
    {
        if (!(Math.Abs(a - b) <= tol)) throw new Exception($"check failed: {what}: {a} vs {b}");
    }

    // version and ABI
    static void Test0()
    {
        Library.CheckAbi();
        Check(Library.Version.Major == Library.AbiMajor, "major");
        Check(Library.StatusName(Status.NotADisk) == "MCON_ERROR_NOT_A_DISK", "status name");
    }

    // mesh from doubles and floats
    static void Test1()
    {
        var r2 = Grid(5); var p = r2.Item1; var t = r2.Item2;
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, p, t)) Check(m.Counts.Vertices == 25 && m.Counts.Triangles == 32, "counts");
        var pf = Array.ConvertAll(p, x => (float)x);
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, new ReadOnlySpan<float>(pf), t)) Check(m.Counts.Vertices == 25, "float counts");
    }

    // invalid mesh throws with status and message
    static void Test2()
    {
        var r3 = Grid(5); var p = r3.Item1; var t = r3.Item2;
        p[3 * 7 + 1] = double.NaN;
        using (var ctx = new Context())
        {
            var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, t));
            Check(e.Status == Status.NonFinite, "status");
            Check(e.Message.Contains("vertex 7"), "message names the vertex: " + e.Message);
            var r4 = Grid(5); var p2 = r4.Item1; var t2 = r4.Item2;
            t2[5] = 999;
            Check(Expect<InvalidMeshException>(() => new Mesh(ctx, p2, t2)).Status == Status.IndexOutOfRange, "range");
            Expect<ArgumentException>(() => new Mesh(ctx, new double[4], t2));
        }
    }

    // patch extraction
    static void Test3()
    {
        var r5 = Grid(41); var p = r5.Item1; var t = r5.Item2;
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
            var r6 = patch.HostVertices(); var v0 = r6.Item1; var v1 = r6.Item2; var s = r6.Item3;
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
    }

    // patch extraction around a point of a triangle, with Python's arguments
    static void TestExtractAtTriangle()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        const uint tri = 2 * (20 * 40 + 20);  // Grid: triangles (a, b, c), (a, c, d) per cell; cell (20, 20): 840, 841, 882
        uint a = t[3 * tri], b = t[3 * tri + 1], c = t[3 * tri + 2];
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, p, t))
        {
            using (var patch = Patch.Extract(m, radius: 0.3, centerTriangle: tri, barycentric: new[] { 0.2, 0.3, 0.5 }))
            {
                var center = patch.Center;
                for (int k = 0; k < 3; ++k)
                    Near(center[k], 0.2 * p[3 * a + k] + 0.3 * p[3 * b + k] + 0.5 * p[3 * c + k], 1e-9, "center on the triangle");
                Check(patch.BoundaryLoops == 1 && Math.Abs(patch.Radius - 0.3) < 1e-12, "a disk of the radius");
                // The same point on the patch's own mesh is its normalization origin.
                var pos = patch.Positions(); var ptri = patch.Triangles(); var bc = patch.CenterBarycentric;
                uint pt = patch.CenterPatchTriangle;
                for (int k = 0; k < 3; ++k)
                {
                    double x = 0;
                    for (int q = 0; q < 3; ++q) x += bc[q] * pos[3 * ptri[3 * pt + q] + k];
                    Near(x, 0, 1e-9, "center at the origin of the patch");
                }
            }
            using (var centroid = Patch.Extract(m, 0.3, centerTriangle: tri))
                for (int k = 0; k < 3; ++k)
                    Near(centroid.Center[k], (p[3 * a + k] + p[3 * b + k] + p[3 * c + k]) / 3, 1e-9, "default: the centroid");
            using (var atCorner = Patch.Extract(m, 0.3, centerTriangle: tri, barycentric: new[] { 1.0, 0, 0 }))
            using (var atVertex = Patch.Extract(m, a, 0.3))
            using (var named = Patch.Extract(m, 0.3, centerVertex: a))
            {
                for (int k = 0; k < 3; ++k) Near(atCorner.Center[k], atVertex.Center[k], 1e-12, "corner = vertex");
                Check(named.VertexCount == atVertex.VertexCount && named.TriangleCount == atVertex.TriangleCount, "both overloads cut alike");
            }
            // snapFraction reaches the library: no snapping and the most snapping cut different meshes.
            using (var none = Patch.Extract(m, 0.3, centerTriangle: tri, snapFraction: 0.0))
            using (var most = Patch.Extract(m, 0.3, centerTriangle: tri, snapFraction: 0.45))
                Check(none.VertexCount > most.VertexCount, $"snapping merges cut points ({none.VertexCount} vs {most.VertexCount})");
            var snap = Expect<MacroconException>(() => Patch.Extract(m, 0.3, centerTriangle: tri, snapFraction: 0.5));
            Check(snap.Status == Status.InvalidArgument && snap.Message.Contains("snap_fraction"), snap.Message);
            var range = Expect<MacroconException>(() => Patch.Extract(m, 0.3, centerTriangle: 99999));
            Check(range.Status == Status.InvalidArgument && range.Message.Contains("99999"), range.Message);
            int calls = 0;
            Expect<CancelledException>(() => Patch.Extract(m, 0.3, centerTriangle: tri, progress: f => ++calls < 2));
            Check(calls == 2, "progress reaches the callback");
            // Checked before any native call.
            Expect<ArgumentException>(() => Patch.Extract(m, 0.3));
            Expect<ArgumentException>(() => Patch.Extract(m, 0.3, centerVertex: a, centerTriangle: tri));
            Expect<ArgumentException>(() => Patch.Extract(m, 0.3, centerTriangle: tri, barycentric: new[] { 0.5, 0.5 }));
            Expect<ArgumentException>(() => Patch.Extract(m, 0.3, centerVertex: a, barycentric: new[] { 1.0, 0, 0 }));
            Expect<ArgumentNullException>(() => Patch.Extract(null, 0.3, centerTriangle: tri));
        }
    }

    // progress cancels and callback exceptions propagate
    static void Test4()
    {
        var r7 = Grid(31); var p = r7.Item1; var t = r7.Item2;
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
    }

    // library: entries round trip through every getter
    static void Test5()
    {
        var r8 = Bumpy(41); var p = r8.Item1; var t = r8.Item2;
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, p, t))
        {
            var ps = Patches(m);
            using (var lib = Filled(ctx, ps))
            {
                Check(lib.Count == 5 && (int)lib.Info.EntryCount == 5, "count");
                Check(lib.Info.Descriptor == RetrievalDescriptor.Curv9 && lib.Info.VocabularySize == 0, "info");
                var patch = ps[1];
                var info = lib.GetEntryInfo(1);
                Check(info.Id != 0 && (int)info.VertexCount == patch.VertexCount && (int)info.TriangleCount == patch.TriangleCount, "entry info");
                Check(lib.GetEntryString(1, EntryString.Name) == "entry 1" && lib.GetEntryString(1, EntryString.ClassLabel) == "bump", "strings");
                Check(lib.GetEntryString(1, EntryString.Author) == "mono" && lib.GetEntryString(1, EntryString.Licence) == "CC0-1.0", "author");
                var tags = lib.GetEntryTags(1);
                Check(tags.Length == 2 && tags[0] == "test" && tags[1] == "k1", "tags");
                var pos = patch.Positions(); var got = lib.GetEntryPositions(1);
                for (int i = 0; i < pos.Length; ++i) Near(got[i], pos[i], 1e-5, "positions");
                var tri = patch.Triangles(); var gt = lib.GetEntryTriangles(1);
                for (int i = 0; i < tri.Length; ++i) Check(gt[i] == tri[i], "triangles");
                var lines = lib.GetEntryPolylines(1);
                Check(lines.Length == 2 && lines[0].Kind == PolylineKind.Guide && !lines[0].Closed, "guide");
                Check(lines[1].Kind == PolylineKind.Feature && lines[1].Closed && lines[1].Points.Length == 4, "feature");
                Check(lines[0].Points[1].Face == (uint)patch.TriangleCount / 2, "guide point face");
                Near(lines[0].Points[1].B2, 1.0 / 3, 1e-6, "guide weights");
                var sing = lib.GetEntrySingularities(1);
                Check(sing.Length == 2 && sing[0].IndexQuarters == 1 && sing[1].IndexQuarters == -1 && sing[0].Location.Face == 5, "singularities");
                Near(sing[0].Location.B0, 0.6, 1e-6, "singularity weights");
                var fields = lib.GetEntryFields(1);
                var want = Example(patch, 1).Fields;
                Check(fields.Length == want.Count, "field count");
                for (int f = 0; f < fields.Length; ++f)
                {
                    Check(fields[f].Name == want[f].Name && fields[f].Kind == want[f].Kind && fields[f].Dimension == want[f].Dimension, "field " + f);
                    if (want[f].Kind == FieldKind.IntegerLabel)
                        for (int i = 0; i < want[f].Labels.Length; ++i) Check(fields[f].Labels[i] == want[f].Labels[i], "labels");
                    else
                        for (int i = 0; i < want[f].Values.Length; ++i) Near(fields[f].Values[i], want[f].Values[i], 1e-6, "values");
                }
                var r9 = lib.GetEntryRetrieval(1); var d = r9.Item1; var h = r9.Item2;
                Check(d.Length == 9 * patch.VertexCount && h.Length == 0, "retrieval data before build");
            }
            foreach (var q in ps) q.Dispose();
        }
    }

    // library: save, open, bytes, remove, find, merge
    // A descriptor chosen at creation; name and description survive the bytes; an empty library
    // only changes descriptor, and a NUL in a name is refused before the call.
    static void TestLibraryStrings()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var lib = new ConstraintLibrary(ctx, RetrievalDescriptor.Hks))
        {
            Check(lib.DescriptorName == "hks", "descriptor name " + lib.DescriptorName);
            lib.Name = "bumps \u00e9t\u00e9";
            lib.Description = "two bumps";
            var ps = Patches(m);
            lib.AddEntry(ps[0]);
            Check(lib.Info.DescriptorDimension == 100, "HKS from the first entry: " + lib.Info.DescriptorDimension);
            using (var again = ConstraintLibrary.OpenMemory(ctx, lib.SaveMemory()))
                Check(again.Name == "bumps \u00e9t\u00e9" && again.Description == "two bumps" && again.DescriptorName == "hks",
                      "strings survive: " + again.Name);
            var e = Expect<MacroconException>(() => lib.SetDescriptor(RetrievalDescriptor.Wks));
            Check(e.Status == Status.InvalidArgument && e.Message.Contains("build_retrieval"),
                  "a library with entries: " + e.Message);
            Expect<ArgumentException>(() => lib.Name = "a\0b");
            foreach (var q in ps) q.Dispose();
        }
    }

    static void TestEntryUp()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var lib = new ConstraintLibrary(ctx))
        {
            var ps = Patches(m);
            lib.AddEntry(ps[0]);
            lib.AddEntry(ps[1], new EntryDesc { Up = new[] { 0.0, 0.0, 3.0 } });
            Check(lib.GetEntryUp(0) == null, "an entry without an up reads back none");
            using (var again = ConstraintLibrary.OpenMemory(ctx, lib.SaveMemory()))
            {
                double[] up = again.GetEntryUp(1);
                Check(up != null && up[0] == 0 && up[1] == 0 && up[2] == 3, "the up survives save and open");
                Check(again.GetEntryInfo(1).HasUp == 1 && again.GetEntryInfo(0).HasUp == 0, "EntryInfo.HasUp");
            }
            Expect<ArgumentException>(() => lib.AddEntry(ps[1], new EntryDesc { Up = new[] { 1.0 } }));
            var e = Expect<MacroconException>(() => lib.AddEntry(ps[1], new EntryDesc { Up = new[] { 0.0, 0.0, 0.0 } }));
            Check(e.Status == Status.InvalidArgument && e.Message.Contains("zero vector"), "a zero up: " + e.Message);
            Check(lib.Count == 2, "refused entries are not added");
            foreach (var q in ps) q.Dispose();
        }
    }

    static void Test6()
    {
        var r10 = Bumpy(41); var p = r10.Item1; var t = r10.Item2;
        string dir = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "macrocon-cs-" + System.Diagnostics.Process.GetCurrentProcess().Id);
        System.IO.Directory.CreateDirectory(dir);
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        {
            var ps = Patches(m);
            using (var lib = Filled(ctx, ps))
            {
                var bytes = lib.SaveMemory();
                string path = System.IO.Path.Combine(dir, "lib.mclb");
                lib.Save(path);
                var onDisk = System.IO.File.ReadAllBytes(path);
                Check(onDisk.Length == bytes.Length, "same size");
                for (int i = 0; i < bytes.Length; ++i) Check(onDisk[i] == bytes[i], "same bytes");
                using (var a = ConstraintLibrary.Open(ctx, path))
                using (var b = ConstraintLibrary.OpenMemory(ctx, bytes))
                {
                    Check(a.Count == 5 && b.Count == 5, "reopened");
                    var again = b.SaveMemory();
                    Check(again.Length == bytes.Length, "byte-identical size");
                    for (int i = 0; i < bytes.Length; ++i) Check(again[i] == bytes[i], "byte-identical");
                    Check(a.GetEntryString(4, EntryString.Name) == "entry 4", "names survive");
                }
                ulong id2 = lib.GetEntryInfo(2).Id, id3 = lib.GetEntryInfo(3).Id;
                Check(lib.Find(id2) == 2, "find");
                lib.Remove(id2);
                Check(lib.Count == 4 && lib.Find(id3) == 2, "later entries shift down");
                Check(Expect<NotFoundException>(() => lib.Find(id2)).Status == Status.NotFound, "not found");
                Expect<NotFoundException>(() => lib.Remove(id2));
                using (var other = new ConstraintLibrary(ctx))
                {
                    other.Merge(lib);
                    other.Merge(lib);
                    Check(other.Count == 8, "merged");
                    var ids = new HashSet<ulong>();
                    for (int i = 0; i < 8; ++i) ids.Add(other.GetEntryInfo(i).Id);
                    Check(ids.Count == 8, "renumbered ids");
                }
                string missing = System.IO.Path.Combine(dir, "missing.mclb");
                var fnf = Expect<System.IO.FileNotFoundException>(() => ConstraintLibrary.Open(ctx, missing));
                Check(fnf.FileName == missing && fnf.Message.Contains(missing), "names the path: " + fnf.Message);
                Check(fnf.InnerException is MacroconException && ((MacroconException)fnf.InnerException).Status == Status.IO, "io inside");
                // A path that exists but is no library file stays a MacroconException.
                var notFile = Expect<MacroconException>(() => ConstraintLibrary.Open(ctx, dir));
                Check(notFile.Status == Status.IO, "a folder is an IO error, not a missing file");
                string folder = System.IO.Path.Combine(dir, "no such folder");
                var dnf = Expect<System.IO.DirectoryNotFoundException>(() => lib.Save(System.IO.Path.Combine(folder, "lib.mclb")));
                Check(dnf.Message.Contains(folder) && dnf.InnerException is MacroconException, "names the folder: " + dnf.Message);
                var rosy = new double[3 * ps[0].TriangleCount];
                for (int f = 0; f < ps[0].TriangleCount; ++f) rosy[3 * f] = 1;
                Check(Expect<System.IO.DirectoryNotFoundException>(() => ps[0].WriteRosy(rosy, System.IO.Path.Combine(folder, "f.rosy")))
                      .Message.Contains(folder), "rosy names the folder");
            }
            foreach (var q in ps) q.Dispose();
        }
        System.IO.Directory.Delete(dir, true);
    }

    // library: retrieval finds each entry itself; cancel leaves it unchanged
    static void Test7()
    {
        var r11 = Bumpy(41); var p = r11.Item1; var t = r11.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        {
            var ps = Patches(m);
            using (var lib = Filled(ctx, ps))
            {
                Check(Expect<MacroconException>(() => lib.Query(ps[0], 3)).Status == Status.InvalidArgument, "no vocabulary");
                var before = lib.SaveMemory();
                int calls = 0;
                Expect<CancelledException>(() => lib.BuildRetrieval(new RetrievalSettings { VocabularySize = 16 }, f => ++calls < 1));
                Check(calls == 1 && lib.Info.VocabularySize == 0 && lib.SaveMemory().Length == before.Length, "unchanged after cancel");
                var e = Expect<InvalidOperationException>(() =>
                    lib.BuildRetrieval(new RetrievalSettings { VocabularySize = 16 }, f => throw new InvalidOperationException("from C#")));
                Check(e.Message == "from C#", "the callback's exception");
                double last = -1;
                lib.BuildRetrieval(new RetrievalSettings { VocabularySize = 16, Seed = 7 }, f => { last = f; return true; });
                var info = lib.Info;
                Check(info.VocabularySize > 0 && info.VocabularySize <= 16 && info.HistogramLength == info.VocabularySize * info.Rings, "vocabulary");
                Check(last >= 0 && last <= 1, "progress fractions");
                for (int k = 0; k < ps.Length; ++k)
                {
                    var r = lib.Query(ps[k], 3);
                    Check(r.Count == 3 && r.Indices[0] == k && r.Ids[0] == lib.GetEntryInfo(k).Id, "self first " + k);
                    Check(r.Distances[0] <= r.Distances[1] && r.Distances[1] <= r.Distances[2] && r.Distances[0] < 1e-6, "sorted");
                }
                Check(lib.Query(ps[0], 100).Count == 5, "min(n, count)");
                Expect<ArgumentOutOfRangeException>(() => lib.Query(ps[0], 0));
                var h = lib.GetEntryRetrieval(0).Histogram;
                float sum = 0; foreach (var x in h) sum += x;
                Check(h.Length == info.HistogramLength && sum > 0, "histogram");
            }
            using (var custom = new ConstraintLibrary(ctx))
            {
                foreach (var q in ps)
                {
                    var mc = q.Descriptors(Descriptor.MeanCurvature);
                    var two = new double[2 * mc.Length];
                    for (int i = 0; i < mc.Length; ++i) { two[2 * i] = mc[i]; two[2 * i + 1] = mc[i] * mc[i]; }
                    custom.AddEntry(q, new EntryDesc { Name = "custom", Descriptors = two, DescriptorDimension = 2 });
                }
                custom.BuildRetrieval(new RetrievalSettings { Descriptor = RetrievalDescriptor.Custom, VocabularySize = 8 });
                Check(custom.Info.Descriptor == RetrievalDescriptor.Custom && custom.Info.DescriptorDimension == 2, "custom info");
                var mc2 = ps[2].Descriptors(Descriptor.MeanCurvature);
                var d2 = new double[2 * mc2.Length];
                for (int i = 0; i < mc2.Length; ++i) { d2[2 * i] = mc2[i]; d2[2 * i + 1] = mc2[i] * mc2[i]; }
                Check(custom.QueryDescriptors(ps[2], d2, 2, 2).Indices[0] == 2, "custom query");
                Check(Expect<MacroconException>(() => custom.QueryDescriptors(ps[2], mc2, 1, 2)).Status == Status.InvalidArgument, "dimension");
            }
            foreach (var q in ps) q.Dispose();
        }
    }

    // library: bad input, forged bytes, disposed handles
    static void Test8()
    {
        var r12 = Bumpy(41); var p = r12.Item1; var t = r12.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var patch = Patch.Extract(m, 20 * 41 + 20, 0.22))
        {
            var lib = new ConstraintLibrary(ctx);
            var far = new EntryDesc { Polylines = new[] { new Polyline { Points = new[] { Third(0), Third((uint)patch.TriangleCount + 10) } } } };
            var e = Expect<MacroconException>(() => lib.AddEntry(patch, far));
            Check(e.Status == Status.InvalidArgument && e.Message.Length > 20, "bad face: " + e.Message);
            // A NUL inside a string would cut it short on the C side: rejected before the call.
            var nul = Expect<ArgumentException>(() => lib.AddEntry(patch, new EntryDesc { Name = "uv\0x" }));
            Check(nul.Message.Contains("NUL"), "NUL in a name: " + nul.Message);
            Expect<ArgumentException>(() => lib.AddEntry(patch, new EntryDesc { Tags = new[] { "ok", "a\0b" } }));
            Expect<ArgumentException>(() => lib.Save("dir\0name.mcl"));
            Check(lib.Count == 0, "rejected entries are not stored");
            var nan = new double[patch.VertexCount]; nan[3] = double.NaN;
            Check(Expect<MacroconException>(() => lib.AddEntry(patch, new EntryDesc { Fields = new[] { new Field { Name = "x", Values = nan } } })).Status
                  == Status.NonFinite, "nan field");
            Expect<ArgumentException>(() => lib.AddEntry(patch, new EntryDesc { Fields = new[] { new Field { Name = "x", Values = new double[3] } } }));
            Expect<ArgumentException>(() => lib.AddEntry(patch, new EntryDesc { Fields = new[] { new Field { Name = "x", Kind = FieldKind.IntegerLabel, Values = nan } } }));
            Check(Expect<MacroconException>(() => lib.AddEntry(patch, new EntryDesc { Singularities = new[] { new Singularity(Third(0), 0) } })).Status
                  == Status.InvalidArgument, "zero index");
            Expect<ArgumentNullException>(() => lib.AddEntry(null));
            Check(lib.Count == 0, "unchanged after errors");
            Check(Expect<MacroconException>(() => lib.GetEntryInfo(3)).Status == Status.InvalidArgument, "index range");
            lib.AddEntry(patch, new EntryDesc { Name = "ok" });
            var bytes = lib.SaveMemory();
            Expect<InvalidLibraryException>(() => ConstraintLibrary.OpenMemory(ctx, System.Text.Encoding.ASCII.GetBytes("not a library, just bytes")));
            foreach (int cut in new[] { 8, bytes.Length / 2, bytes.Length - 1 })
                Expect<InvalidLibraryException>(() => ConstraintLibrary.OpenMemory(ctx, new ReadOnlySpan<byte>(bytes, 0, cut)));
            var rng = new Random(5);
            int rejected = 0;
            for (int r = 0; r < 40; ++r)
            {
                var forged = (byte[])bytes.Clone();
                for (int k = 0; k < 4; ++k) forged[rng.Next(forged.Length)] ^= 0xFF;
                try { using (var x = ConstraintLibrary.OpenMemory(ctx, forged)) Check(x.Count >= 0, "opened"); }
                catch (InvalidLibraryException) { ++rejected; }
                catch (MacroconException u) when (u.Status == Status.Unsupported) { ++rejected; }
            }
            Check(rejected > 0, "some forgeries rejected");
            lib.Dispose();
            lib.Dispose();
            Expect<ObjectDisposedException>(() => { var c = lib.Count; });
            Expect<ArgumentNullException>(() => new ConstraintLibrary(null));
        }
    }

    // map: from arrays, compute, correspondences, transfer, cross field
    static void Test9()
    {
        var r13 = Bumpy(41); var p = r13.Item1; var t = r13.Item2;
        string dir = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "macrocon-cs-map-" + System.Diagnostics.Process.GetCurrentProcess().Id);
        System.IO.Directory.CreateDirectory(dir);
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var target = Patch.Extract(m, 21 * 41 + 20, 0.25))
        using (var source = Patch.FromArrays(ctx, target.Positions(), target.Triangles(), target.CenterPatchTriangle,
                                             target.CenterBarycentric, target.Center, target.Radius))
        {
            Check(source.VertexCount == target.VertexCount && source.BoundaryLoops == 1, "from arrays");
            var r14 = source.HostVertices(); var hv0 = r14.Item1; var hv1 = r14.Item2; var ht = r14.Item3;
            for (int v = 0; v < source.VertexCount; ++v) Check(hv0[v] == v && hv1[v] == v && ht[v] == 0, "identity host");
            Expect<NotADiskException>(() => Patch.FromArrays(ctx,
                new double[] { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 },
                new uint[] { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 }, 0));
            Check(Expect<MacroconException>(() => Patch.FromArrays(ctx, target.Positions(), target.Triangles(), Native_InvalidIndex)).Status
                  == Status.InvalidArgument, "invalid center");
            var settings = new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30 };
            int calls = 0;
            Expect<CancelledException>(() => Map.Compute(source, target, settings, f => ++calls < 1));
            Check(calls == 1, "one progress call before cancel");
            Check(Expect<MacroconException>(() => Map.Compute(source, target, new MapSettings { AlignmentSamples = 0 })).Status
                  == Status.InvalidArgument, "bad options");
            using (var map = Map.Compute(source, target, settings))
            {
                var info = map.Info;
                Check((int)info.SourceVertexCount == source.VertexCount && (int)info.TargetVertexCount == target.VertexCount, "counts");
                Check(info.FlippedTriangles == 0 && info.Reflected == 0 && info.MatchingScore >= 0 && info.MatchingScore <= 1, "info");
                Check((int)info.SourceVerticesInside > 0.8 * source.VertexCount, "overlap");
                var terms = map.EnergyTerms;
                Check(terms.Length >= 4 && terms[0].Name == "descriptor" && terms[3].Name == "injectivity", "energy term names");
                Check(terms[0].Value == info.EnergyDescriptor && terms[2].Value == info.EnergyArea, "energy term values");
                var r15 = map.Correspondences(MapDirection.SourceToTarget); var ct = r15.Item1; var cb = r15.Item2;
                int inside = 0;
                for (int v = 0; v < ct.Length; ++v)
                    if (ct[v] >= 0) { ++inside; Near(cb[3 * v] + cb[3 * v + 1] + cb[3 * v + 2], 1, 1e-9, "weights sum"); }
                Check(inside == (int)info.SourceVerticesInside, "inside count");
                var r16 = map.Correspondences(MapDirection.TargetToSource); var rt = r16.Item1;
                Check(rt.Length == target.VertexCount, "reverse size");
                var mask = map.OutsideMask();
                int outside = 0; foreach (var o in mask) if (o) ++outside;
                Check(outside == target.VertexCount - (int)info.TargetVerticesInside, "outside mask");
                Check(map.Phi().Length == 2 * source.VertexCount, "phi");
                var spos = source.Positions();
                var moved = map.TransferField(FieldKind.Vector3, 3, spos);
                var tpos = target.Positions();
                var errs = new List<double>();
                for (int v = 0; v < target.VertexCount; ++v)
                {
                    if (mask[v]) { Check(moved[3 * v] == 0 && moved[3 * v + 1] == 0 && moved[3 * v + 2] == 0, "outside is 0"); continue; }
                    double dx = moved[3 * v] - tpos[3 * v], dy = moved[3 * v + 1] - tpos[3 * v + 1], dz = moved[3 * v + 2] - tpos[3 * v + 2];
                    errs.Add(Math.Sqrt(dx * dx + dy * dy + dz * dz));
                }
                errs.Sort();
                Check(errs[errs.Count / 2] < 0.1, "near identity: median " + errs[errs.Count / 2]);
                var labels = new int[source.VertexCount];
                for (int v = 0; v < labels.Length; ++v) labels[v] = v % 5;
                var tl = map.TransferLabels(1, labels, -7);
                for (int v = 0; v < tl.Length; ++v) Check(mask[v] ? tl[v] == -7 : tl[v] >= 0 && tl[v] < 5, "labels never blended");
                Expect<ArgumentException>(() => map.TransferField(FieldKind.Scalar, 1, new double[3]));
                Expect<ArgumentException>(() => map.TransferField(FieldKind.IntegerLabel, 1, spos));
                Check(Expect<MacroconException>(() => map.TransferField(FieldKind.Vector3, 2, source.Uv())).Status == Status.InvalidArgument, "vector3 needs 3");
                var r17 = map.TransferPoints(new uint[] { 0, 7, 14 }, new double[] { 0.2, 0.3, 0.5, 0.2, 0.3, 0.5, 0.2, 0.3, 0.5 }); var pt = r17.Item1; var pb = r17.Item2; var px = r17.Item3;
                Check(pt.Length == 3 && pb.Length == 9 && px.Length == 9, "points");
                Expect<ArgumentException>(() => map.TransferPoints(new uint[] { 0 }, new double[] { 1 }));
                // A guide along the source triangles whose uv centroid lies near v = 0.
                var uv = source.Uv(); var tri = source.Triangles();
                var rowU = new List<double>(); var rowF = new List<uint>();
                for (int f = 0; f < source.TriangleCount; ++f)
                {
                    double cu = 0, cv = 0;
                    for (int c = 0; c < 3; ++c) { cu += uv[2 * tri[3 * f + c]] / 3; cv += uv[2 * tri[3 * f + c] + 1] / 3; }
                    if (Math.Abs(cv) < 0.05) { rowU.Add(cu); rowF.Add((uint)f); }
                }
                var keys = rowU.ToArray(); var faces = rowF.ToArray();
                Array.Sort(keys, faces);
                var guidePoints = new SurfacePoint[faces.Length];
                for (int i = 0; i < faces.Length; ++i) guidePoints[i] = Third(faces[i]);
                var guide = new Polyline { Points = guidePoints };
                using (var lines = map.TransferPolylines(new[] { guide }))
                {
                    var r18 = lines.Counts; var np = r18.Item1; var npts = r18.Item2;
                    Check(np >= 1 && npts >= faces.Length / 2, "re-traced");
                    var r19 = lines.Polylines(); var sizes = r19.Item1; var closed = r19.Item2; var input = r19.Item3;
                    long total = 0; foreach (var s in sizes) total += s;
                    Check(total == npts && !closed[0] && input[0] == 0, "polyline arrays");
                    var r20 = lines.Points(); var lt = r20.Item1; var lb = r20.Item2; var lx = r20.Item3;
                    foreach (var f in lt) Check(f < target.TriangleCount, "on the target");
                    for (int i = 0; i < lt.Length; ++i) Near(lb[3 * i] + lb[3 * i + 1] + lb[3 * i + 2], 1, 1e-9, "point weights");
                    foreach (var x in lx) Check(!double.IsNaN(x) && !double.IsInfinity(x), "finite 3D points");
                    var r21 = target.CrossField(lines, 10.0); var dirs = r21.Item1; var conf = r21.Item2;
                    Check(dirs.Length == 3 * target.TriangleCount && conf.Length == target.TriangleCount, "cross field size");
                    for (int f = 0; f < target.TriangleCount; ++f)
                    {
                        Near(Math.Sqrt(dirs[3 * f] * dirs[3 * f] + dirs[3 * f + 1] * dirs[3 * f + 1] + dirs[3 * f + 2] * dirs[3 * f + 2]), 1, 1e-6, "unit");
                        Check(conf[f] >= 0 && conf[f] <= 1, "confidence");
                    }
                    Check(Expect<MacroconException>(() => source.CrossField(lines)).Status == Status.InvalidArgument, "guides of another patch");
                    string rosy = System.IO.Path.Combine(dir, "f.rosy");
                    target.WriteRosy(dirs, rosy);
                    Check(System.IO.File.ReadAllText(rosy).Contains(target.TriangleCount.ToString()), "rosy header");
                    var io = Expect<System.IO.DirectoryNotFoundException>(() => target.WriteRosy(dirs, System.IO.Path.Combine(dir, "no", "f.rosy")));
                    Check(((MacroconException)io.InnerException).Status == Status.IO, "io");
                    Expect<ArgumentException>(() => target.WriteRosy(new double[3], rosy));
                }
                var smooth = target.CrossField();
                Check(smooth.Directions.Length == 3 * target.TriangleCount, "smoothest field");
            }
            var disposed = Map.Compute(source, target, settings);
            disposed.Dispose();
            Expect<ObjectDisposedException>(() => { var i = disposed.Info; });
            Expect<ArgumentNullException>(() => Map.Compute(null, target));
        }
        System.IO.Directory.Delete(dir, true);
    }

    // The source triangle whose uv contains (u, v), as a surface point (false if none).
    static bool LocateUv(double[] uv, uint[] tri, double u, double v, out SurfacePoint point)
    {
        for (int f = 0; f < tri.Length / 3; ++f)
        {
            uint a = tri[3 * f], b = tri[3 * f + 1], c = tri[3 * f + 2];
            double x0 = uv[2 * a], y0 = uv[2 * a + 1], x1 = uv[2 * b], y1 = uv[2 * b + 1], x2 = uv[2 * c], y2 = uv[2 * c + 1];
            double det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2);
            if (det == 0) continue;
            double l0 = ((y1 - y2) * (u - x2) + (x2 - x1) * (v - y2)) / det;
            double l1 = ((y2 - y0) * (u - x2) + (x0 - x2) * (v - y2)) / det;
            double l2 = 1 - l0 - l1;
            if (l0 >= -1e-12 && l1 >= -1e-12 && l2 >= -1e-12) { point = new SurfacePoint((uint)f, l0, l1, l2); return true; }
        }
        point = default(SurfacePoint);
        return false;
    }

    static ulong EdgeKey(uint a, uint b) => a < b ? ((ulong)a << 32) | b : ((ulong)b << 32) | a;

    // cut mesh: guides transferred by the map of Test9 (a closed loop and a line across it, as in
    // tests/capi/test_capi_cut_mesh.cpp) cut into the target; chains of edges, host points,
    // carried fields, cross field, QuadWild's files, bad arguments.
    static void TestCutMesh()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        string dir = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "macrocon-cs-cut-" + System.Diagnostics.Process.GetCurrentProcess().Id);
        System.IO.Directory.CreateDirectory(dir);
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var target = Patch.Extract(m, 21 * 41 + 20, 0.25))
        using (var source = Patch.FromArrays(ctx, target.Positions(), target.Triangles(), target.CenterPatchTriangle,
                                             target.CenterBarycentric, target.Center, target.Radius))
        using (var map = Map.Compute(source, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30 }))
        {
            var uv = source.Uv(); var stri = source.Triangles();
            var loop = new SurfacePoint[30];
            for (int i = 0; i < 30; ++i)
                Check(LocateUv(uv, stri, 0.4 * Math.Cos(2 * Math.PI * i / 30), 0.4 * Math.Sin(2 * Math.PI * i / 30), out loop[i]), "loop point " + i);
            var across = new SurfacePoint[2];
            Check(LocateUv(uv, stri, -0.6, -0.05, out across[0]) && LocateUv(uv, stri, 0.6, 0.08, out across[1]), "line points");
            using (var guides = map.TransferPolylines(new[] { new Polyline { Points = loop, Closed = true }, new Polyline { Points = across } }))
            using (var cut = target.CutGuides(guides))
            {
                var info = cut.Info;
                Check(info.GuideEdgeCount.ToUInt64() > 0, "guide edges");
                Check((int)info.TriangleCount > target.TriangleCount && (int)info.GuideCount == guides.Counts.Polylines, "info: " +
                      info.TriangleCount + " triangles, " + info.GuideCount + " guides");
                var xyz = cut.Positions(); var tri = cut.Triangles();
                Check(xyz.Length == 3 * (int)info.VertexCount && tri.Length == 3 * (int)info.TriangleCount, "array sizes");
                // Each vertex is at its host point on the patch (host = center + radius * normalized).
                var ht = cut.HostTriangles(); var hb = cut.HostBarycentric();
                var tpos = target.Positions(); var ttri = target.Triangles(); var center = target.Center;
                for (int v = 0; v < (int)info.VertexCount; ++v)
                    for (int k = 0; k < 3; ++k)
                    {
                        double q = 0;
                        for (int c = 0; c < 3; ++c) q += hb[3 * v + c] * tpos[3 * ttri[3 * ht[v] + c] + k];
                        Near(center[k] + target.Radius * q, xyz[3 * v + k], 1e-9, "host point of vertex " + v);
                    }
                // Every chain is a path of mesh edges; the guide edges are exactly the chains' steps.
                var meshEdges = new HashSet<ulong>();
                for (int f = 0; f < tri.Length / 3; ++f)
                    for (int k = 0; k < 3; ++k) meshEdges.Add(EdgeKey(tri[3 * f + k], tri[3 * f + (k + 1) % 3]));
                var chains = cut.Guides();
                Check(chains.Length == (int)info.GuideCount, "one chain per guide");
                var steps = new HashSet<ulong>();
                long chainVertices = 0;
                foreach (var chain in chains)
                {
                    chainVertices += chain.Length;
                    for (int k = 0; k + 1 < chain.Length; ++k)
                    {
                        Check(meshEdges.Contains(EdgeKey(chain[k], chain[k + 1])), $"chain step {chain[k]}-{chain[k + 1]} is a mesh edge");
                        steps.Add(EdgeKey(chain[k], chain[k + 1]));
                    }
                }
                Check(chainVertices == (long)info.GuideVertexCount, "chain vertices");
                var ge = cut.GuideEdges();
                Check(ge.Length == 2 * (int)info.GuideEdgeCount, "guide edge array");
                var listed = new HashSet<ulong>();
                for (int e = 0; e < ge.Length / 2; ++e) listed.Add(EdgeKey(ge[2 * e], ge[2 * e + 1]));
                Check(listed.SetEquals(steps), "guide edges are the chains' steps");
                // The patch's host-unit x coordinate, carried, is the cut vertices' x.
                var field = new double[target.VertexCount];
                for (int v = 0; v < field.Length; ++v) field[v] = center[0] + target.Radius * tpos[3 * v];
                var carried = cut.CarryField(field, 1);
                Check(carried.Length == (int)info.VertexCount, "carried size");
                for (int v = 0; v < carried.Length; ++v) Near(carried[v], xyz[3 * v], 1e-9, "carried x of vertex " + v);
                Check(cut.CarryField(tpos, 3).Length == 3 * (int)info.VertexCount, "dimension 3");
                Expect<ArgumentException>(() => cut.CarryField(new double[field.Length + 1], 1));
                Expect<ArgumentException>(() => cut.CarryField(field, 0));
                var nan = (double[])field.Clone(); nan[3] = double.NaN;
                Check(Expect<InvalidMeshException>(() => cut.CarryField(nan, 1)).Status == Status.NonFinite, "NaN field");
                // The cross field: unit directions, one per triangle.
                var dirs = cut.CrossField();
                Check(dirs.Length == 3 * (int)info.TriangleCount, "cross field size");
                for (int f = 0; f < dirs.Length / 3; ++f)
                    Near(Math.Sqrt(dirs[3 * f] * dirs[3 * f] + dirs[3 * f + 1] * dirs[3 * f + 1] + dirs[3 * f + 2] * dirs[3 * f + 2]), 1, 1e-6, "unit");
                // QuadWild's three files agree with the cut mesh.
                string prefix = System.IO.Path.Combine(dir, "cut");
                cut.WriteQuadWild(prefix);
                var obj = System.IO.File.ReadAllLines(prefix + ".obj");
                int faces = 0, vertices = 0;
                foreach (var line in obj) { if (line.StartsWith("f ")) ++faces; if (line.StartsWith("v ")) ++vertices; }
                Check(faces == (int)info.TriangleCount && vertices == (int)info.VertexCount, $".obj: {vertices} v, {faces} f");
                Check(long.Parse(System.IO.File.ReadAllLines(prefix + ".rosy")[0].Trim()) == (long)info.TriangleCount, ".rosy count");
                Check(long.Parse(System.IO.File.ReadAllLines(prefix + ".sharp")[0].Trim()) == (long)info.GuideEdgeCount, ".sharp count");
                var io = Expect<System.IO.DirectoryNotFoundException>(() => cut.WriteQuadWild(System.IO.Path.Combine(dir, "no", "cut")));
                Check(((MacroconException)io.InnerException).Status == Status.IO, "io");
                Check(Expect<MacroconException>(() => cut.WriteQuadWild("")).Status == Status.InvalidArgument, "empty prefix");
                Expect<ArgumentNullException>(() => cut.WriteQuadWild(null));
                // Bad arguments: a snap fraction out of range, guides of another patch, no guides.
                var bad = Expect<MacroconException>(() => target.CutGuides(guides, snapFraction: 0.6));
                Check(bad.Status == Status.InvalidArgument && bad.Message.Contains("snap_fraction"), "bad snap fraction: " + bad.Message);
                Check(Expect<InvalidMeshException>(() => target.CutGuides(guides, snapFraction: double.NaN)).Status == Status.NonFinite, "NaN snap");
                var other = Expect<MacroconException>(() => source.CutGuides(guides));
                Check(other.Status == Status.InvalidArgument && other.Message.Contains("another patch"), "guides of another patch: " + other.Message);
                Expect<ArgumentNullException>(() => target.CutGuides(null));
                // Fairing is on by default; 0 passes cuts the same triangles with unmoved chains.
                using (var raw = target.CutGuides(guides, fairPasses: 0))
                    Check(raw.Info.FairedVertices == 0 && cut.Info.FairedVertices > 0 && raw.Info.TriangleCount == cut.Info.TriangleCount,
                          "fairing: " + cut.Info.FairedVertices + " faired by default, " + raw.Info.FairedVertices + " with 0 passes");
                Check(Expect<MacroconException>(() => target.CutGuides(guides, fairPasses: 101)).Message.Contains("fair_passes"), "fair_passes 101");
                // Explicit fractions give a valid cut too; a disposed cut mesh throws.
                using (var fine = target.CutGuides(guides, snapFraction: 0.0, simplifyFraction: 0.0))
                    Check(fine.Info.GuideEdgeCount.ToUInt64() > 0, "explicit fractions");
                // The whole host: every face of the mesh, its host points on mesh triangles, a mesh field carried.
                using (var whole = m.CutGuides(new[] { guides }))
                {
                    var wi = whole.Info;
                    Check((int)wi.TriangleCount > m.Counts.Triangles && wi.GuideEdgeCount.ToUInt64() > 0 && wi.UnplacedPoints == 0,
                          "whole host: " + wi.TriangleCount + " triangles");
                    var origins = whole.GuideOrigins();
                    Check(origins.Length == (int)wi.GuideCount && origins[0].Set == 0, "guide origins");
                    var wx = whole.Positions();
                    var y = new double[m.Counts.Vertices];
                    for (int v = 0; v < y.Length; ++v) y[v] = p[3 * v + 1];
                    var wy = whole.CarryField(y, 1);
                    for (int v = 0; v < wy.Length; ++v) Near(wy[v], wx[3 * v + 1], 1e-9, "carried y of vertex " + v);
                    Check(whole.CrossField().Length == 3 * (int)wi.TriangleCount, "whole-host cross field");
                }
                var moved = (double[])p.Clone();
                for (int v = 0; v < moved.Length; v += 3) moved[v] += 0.01;
                using (var otherMesh = new Mesh(ctx, moved, t))
                {
                    var notCut = Expect<MacroconException>(() => otherMesh.CutGuides(new[] { guides }));
                    Check(notCut.Status == Status.InvalidArgument && notCut.Message.Contains("not cut from this mesh"), "other mesh: " + notCut.Message);
                }
                Expect<ArgumentNullException>(() => m.CutGuides(new PolylineSet[] { null }));
            }
            using (var line = map.TransferPolylines(new[] { new Polyline { Points = across } }))
            {
                var disposed = target.CutGuides(line);
                disposed.Dispose();
                Expect<ObjectDisposedException>(() => { var i = disposed.Info; });
            }
        }
        System.IO.Directory.Delete(dir, true);
    }

    // map: forced orientation (the "flip" workflow) and the evidence of the automatic call
    static void TestOrientation()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var target = Patch.Extract(m, 21 * 41 + 20, 0.25))
        using (var source = Patch.FromArrays(ctx, target.Positions(), target.Triangles(), 0, null, target.Center, target.Radius))
        {
            Check(new MapSettings().Orientation == MapOrientation.Automatic, "default automatic");
            var settings = new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30 };
            MapInfo a;
            using (var map = Map.Compute(source, target, settings)) a = map.Info;
            Check(a.FrameDecided == 0, "frame-free by default");
            using (var framed = Map.Compute(source, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30, UseWorldFrame = true }))
                Check(framed.Info.FrameDecided == 1 && framed.Info.Reflected == 0, "the world frame decides when asked");
            using (var unanchored = Map.Compute(source, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30, UseWorldFrame = true, WorldFrameAnchor = 0 }))
                Check(Array.Exists(unanchored.EnergyTerms, e => e.Name == "anchor" && e.Value == 0), "anchor 0: the term is off");
            var badAnchor = Expect<MacroconException>(() => Map.Compute(source, target, new MapSettings { UseWorldFrame = true, WorldFrameAnchor = -1 }));
            Check(badAnchor.Status == Status.InvalidArgument && badAnchor.Message.Contains("world_frame_anchor"), "negative anchor: " + badAnchor.Message);
            using (var hinted = Map.Compute(source, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30, SourceUp = new[] { 0.0, 1, 0 }, TargetUp = new[] { 0.0, 1, 0 } }))
                Check(hinted.Info.FlippedTriangles == 0, "up hints: a map");
            Expect<ArgumentException>(() => Map.Compute(source, target, new MapSettings { SourceUp = new[] { 0.0, 1, 0 } }));
            var zeroUp = Expect<MacroconException>(() => Map.Compute(source, target, new MapSettings { SourceUp = new[] { 0.0, 0, 0 }, TargetUp = new[] { 0.0, 1, 0 } }));
            Check(zeroUp.Status == Status.InvalidArgument && zeroUp.Message.Contains("source_up"), "zero up: " + zeroUp.Message);
            Check(a.AlignmentScoreUnreflected >= 0 && a.AlignmentScoreReflected >= 0, "both rigid scores");
            Check(a.AlignmentScore == (a.Reflected != 0 ? a.AlignmentScoreReflected : a.AlignmentScoreUnreflected), "winner's score");
            Check(a.OrientationCompared != 0
                      ? a.Level0EnergyUnreflected > 0 && a.Level0EnergyReflected > 0
                      : a.Level0EnergyUnreflected == -1 && a.Level0EnergyReflected == -1, "level-0 energies");
            foreach (var forced in new[] { MapOrientation.Preserve, MapOrientation.Reverse })
            {
                settings.Orientation = forced;
                using (var map = Map.Compute(source, target, settings))
                {
                    var i = map.Info;
                    Check(i.Reflected == (forced == MapOrientation.Reverse ? 1u : 0u), forced + ": reflected " + i.Reflected);
                    Check(i.FlippedTriangles == 0 && i.OrientationCompared == 0, forced + ": injective, not compared");
                    Check(i.Level0EnergyUnreflected == -1 && i.Level0EnergyReflected == -1, forced + ": no level-0 energies");
                    Check(i.AlignmentScoreUnreflected == a.AlignmentScoreUnreflected &&
                          i.AlignmentScoreReflected == a.AlignmentScoreReflected, forced + ": same rigid scores");
                }
            }
            settings.Orientation = (MapOrientation)7;
            Check(Expect<MacroconException>(() => Map.Compute(source, target, settings)).Status == Status.InvalidArgument,
                  "bad orientation");
            // The refinement pass after the finest level: a stage of its own by default, off with 0.
            settings.Orientation = MapOrientation.Automatic;
            Check(!new MapSettings().RefineSigmaFactor.HasValue, "the default refinement factor is the library's");
            Check(a.Levels == 4, "default levels " + a.Levels);
            settings.RefineSigmaFactor = 0;
            using (var map = Map.Compute(source, target, settings)) Check(map.Info.Levels == 3, "no refinement: 3 levels");
            settings.RefineSigmaFactor = 1.5;
            Check(Expect<MacroconException>(() => Map.Compute(source, target, settings)).Status == Status.InvalidArgument,
                  "bad refinement factor");
            // Coarse to fine in mesh resolution: reported in the info, off with CoarseStages 0, range-checked.
            settings.RefineSigmaFactor = null;
            settings.CoarseVertices = (uint)Math.Max(100, source.VertexCount / 3);
            using (var map = Map.Compute(source, target, settings))
                Check(source.VertexCount < 300 || (map.Info.CoarseStages >= 1 && map.Info.CoarseVertices >= settings.CoarseVertices &&
                      map.Info.CoarseFallback == 0), "coarse stages on a coarse copy: " + map.Info.CoarseVertices);
            settings.CoarseStages = 0;
            using (var map = Map.Compute(source, target, settings)) Check(map.Info.CoarseVertices == 0, "coarse stages off");
            settings.CoarseStages = 9;
            Check(Expect<MacroconException>(() => Map.Compute(source, target, settings)).Status == Status.InvalidArgument,
                  "bad coarse stages");
        }
    }

    // A flat disk onto itself fits any rotation: guidance pairing p with R p must make it that rotation.
    static void TestGuidance()
    {
        var r = Grid(41); var p = r.P; var t = r.T;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
        using (var disk = Patch.Extract(m, 20 * 41 + 20, 0.3))
        {
            double[] xyz = disk.Positions();
            int n = xyz.Length / 3;
            double angle = 2.0, c = Math.Cos(angle), s = Math.Sin(angle);
            var gs = new double[2 * n]; var gt = new double[2 * n];
            for (int v = 0; v < n; ++v)
            {
                double x = xyz[3 * v], y = xyz[3 * v + 1];
                gs[2 * v] = x; gs[2 * v + 1] = y;
                gt[2 * v] = c * x + s * y; gt[2 * v + 1] = -s * x + c * y;  // R^-1 p
            }
            var settings = new MapSettings { Seed = 3, AlignmentSamples = 400, SourceGuidance = gs, TargetGuidance = gt,
                                             GuidanceDimension = 2, GuidanceWeight = 10 };
            using (var map = Map.Compute(disk, disk, settings))
            {
                Check(map.Info.Reflected == 0, "guided map keeps the orientation");
                var corr = map.Correspondences(MapDirection.SourceToTarget);
                uint[] tris = disk.Triangles();
                double err = 0; int inside = 0;
                for (int v = 0; v < n; ++v)
                {
                    int f = corr.Triangles[v];
                    if (f < 0) continue;
                    double qx = 0, qy = 0;
                    for (int k = 0; k < 3; ++k)
                    {
                        uint w = tris[3 * f + k];
                        qx += corr.Barycentric[3 * v + k] * xyz[3 * w];
                        qy += corr.Barycentric[3 * v + k] * xyz[3 * w + 1];
                    }
                    double x = xyz[3 * v], y = xyz[3 * v + 1];
                    err += Math.Sqrt(Math.Pow(qx - (c * x - s * y), 2) + Math.Pow(qy - (s * x + c * y), 2));
                    ++inside;
                }
                Check(inside > n * 3 / 4, "inside " + inside + " of " + n);
                Check(err / inside < 0.05, "mean error " + err / inside + " (no rotation would be ~1.1)");
            }
            settings.TargetGuidance = null;
            Expect<ArgumentException>(() => Map.Compute(disk, disk, settings));
            settings.TargetGuidance = new double[2 * n - 1];
            Expect<ArgumentException>(() => Map.Compute(disk, disk, settings));
            var bad = (double[])gt.Clone(); bad[7] = double.NaN;
            settings.TargetGuidance = bad;
            Check(Expect<MacroconException>(() => Map.Compute(disk, disk, settings)).Status == Status.NonFinite, "NaN guidance");
            settings.TargetGuidance = gt; settings.GuidanceWeight = -1;
            Check(Expect<MacroconException>(() => Map.Compute(disk, disk, settings)).Status == Status.InvalidArgument,
                  "negative guidance weight");
        }
    }

    // heavy parallel work then shutdown
    static void Test10()
    {
        var r22 = Grid(81); var p = r22.Item1; var t = r22.Item2;
        using (var ctx = new Context())
        using (var m = new Mesh(ctx, p, t))
            for (int i = 0; i < 3; ++i)
                using (var patch = Patch.Extract(m, 40 * 81 + 40, 0.2 + 0.1 * i)) patch.Descriptors(Descriptor.Curv9);
    }

    // winding: a host with reversed triangles is repaired, reported, and gives the same patch
    static void TestWinding()
    {
        var r = Bumpy(31); var p = r.P; var t = r.T;
        var flipped = (uint[])t.Clone();
        int reversed = 0;
        for (int f = 0; f < flipped.Length / 3; f += 3)
        {
            uint corner1 = flipped[3 * f + 1];
            flipped[3 * f + 1] = flipped[3 * f + 2];
            flipped[3 * f + 2] = corner1;
            ++reversed;
        }
        using (var ctx = new Context())
        using (var a = new Mesh(ctx, p, t))
        using (var b = new Mesh(ctx, p, flipped))
        using (var pa = Patch.Extract(a, 15 * 31 + 15, 0.3))
        using (var pb = Patch.Extract(b, 15 * 31 + 15, 0.3))
        {
            var oa = a.Orientation; var ob = b.Orientation;
            Check(oa.Components == 1 && ob.Components == 1, "one component");
            Check(ob.InconsistentComponents == 1, "inconsistent input reported");
            Check(ob.ReorientedTriangles == reversed || ob.ReorientedTriangles == t.Length / 3 - reversed, "reoriented count " + ob.ReorientedTriangles);
            Check(System.Linq.Enumerable.SequenceEqual(a.Triangles(), b.Triangles()), "same oriented triangles");
            var flags = b.ReorientedTriangles();
            Check(flags.Length == t.Length / 3, "one flag per triangle");
            Check(pb.HostReorientedTriangles == ob.ReorientedTriangles && pb.HostInconsistentComponents == 1, "patch info reports the host repair");
            Check(System.Linq.Enumerable.SequenceEqual(pa.Descriptors(Descriptor.Curv9), pb.Descriptors(Descriptor.Curv9)), "same descriptors");
            var disagree = new uint[] { 0, 1, 2, 1, 2, 3 };
            var quad = new double[] { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0 };
            // Two triangles that share edge (1, 2) in the same direction are repaired, not rejected.
            using (var two = new Mesh(ctx, quad, disagree)) Check(two.Orientation.ReorientedTriangles == 1, "two-triangle repair");
        }
    }

    // MeshFlags.ValidateLocally: a duplicated triangle far from the patch is accepted and changes
    // nothing; a patch that reads it, and the whole-host cut, report it.
    static void TestValidateLocally()
    {
        var g = Grid(31); var p = g.P;
        int dup = 6 * (28 * 30 + 28);
        var t = new List<uint>(g.T);
        t.AddRange(new[] { g.T[dup], g.T[dup + 1], g.T[dup + 2] });
        var bad = t.ToArray();
        using (var ctx = new Context())
        {
            var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, bad));
            Check(e.Status == Status.NonManifoldEdge, "whole-mesh validation by default: " + e.Status);
            using (var mesh = new Mesh(ctx, p, bad, MeshFlags.ValidateLocally))
            using (var clean = new Mesh(ctx, p, g.T))
            using (var a = Patch.Extract(mesh, 10 * 31 + 10, 0.1))
            using (var b = Patch.Extract(clean, 10 * 31 + 10, 0.1))
            {
                Check(System.Linq.Enumerable.SequenceEqual(a.Positions(), b.Positions()), "same patch as on the clean host");
                var near = Expect<InvalidMeshException>(() => Patch.Extract(mesh, 27 * 31 + 27, 0.05));
                Check(near.Status == Status.NonManifoldEdge && near.Message.Contains("within 3 radii"), near.Message);
                var whole = Expect<InvalidMeshException>(() => mesh.CutGuides(new PolylineSet[0]));
                Check(whole.Message.Contains("reads the whole mesh"), whole.Message);
            }
        }
    }

    // Patch.Extract(..., repair: true): a zero-area cap on the bottom edge and a sheet glued at an
    // interior vertex are repaired, and Repairs says so; without the flag both are refused.
    static void TestRepair()
    {
        int n = 31; var g = Grid(n);
        var p = new List<double>(g.P); var t = new List<uint>(g.T);
        uint a = 5, b = 6, pin = (uint)(15 * n + 15);
        p.AddRange(new[] { (g.P[3 * a] + g.P[3 * b]) / 2, 0.0, 0.0 });
        p.AddRange(new[] { g.P[3 * pin] + 0.1, g.P[3 * pin + 1], 0.2, g.P[3 * pin], g.P[3 * pin + 1] + 0.1, 0.2 });
        uint mid = (uint)(n * n), u = mid + 1, w = mid + 2;
        t.AddRange(new[] { b, a, mid, pin, u, w });
        using (var ctx = new Context())
        using (var mesh = new Mesh(ctx, p.ToArray(), t.ToArray(), MeshFlags.ValidateLocally))
        using (var clean = new Mesh(ctx, g.P, g.T))
        {
            var e = Expect<InvalidMeshException>(() => Patch.Extract(mesh, 0.15, centerVertex: (uint)(n + 5)));
            Check(e.Status == Status.DegenerateTriangle && e.Message.Contains("MCON_PATCH_REPAIR_REGION"), e.Message);
            using (var cap = Patch.Extract(mesh, 0.15, centerVertex: (uint)(n + 5), repair: true))
                Check(cap.Repairs.ZeroAreaTrianglesRemoved == 1 && cap.Repairs.TrianglesSplit == 1, cap.Repairs.ToString());
            using (var pinched = Patch.Extract(mesh, 0.15, centerVertex: pin - 1, repair: true))
            using (var reference = Patch.Extract(clean, 0.15, centerVertex: pin - 1))
            {
                Check(pinched.Repairs.PinchedVerticesSplit == 1, pinched.Repairs.ToString());
                Check(System.Linq.Enumerable.SequenceEqual(pinched.Positions(), reference.Positions()), "the clean host's patch");
            }
        }
    }

    // Every struct handed to the C ABI against macrocon.h: its size and the offset of each field whose
    // snake_case name exists in C, measured by a C probe compiled with `cc` (MACROCON_INCLUDE_DIR).
    static void TestLayout()
    {
        string include = Environment.GetEnvironmentVariable("MACROCON_INCLUDE_DIR");
        Check(!string.IsNullOrEmpty(include) && System.IO.File.Exists(System.IO.Path.Combine(include, "macrocon", "macrocon.h")),
              "MACROCON_INCLUDE_DIR must name the include directory");
        var types = new Dictionary<string, Type>
        {
            { "mcon_context_options", typeof(Native.ContextOptions) }, { "mcon_mesh_desc", typeof(Native.MeshDesc) },
            { "mcon_patch_options", typeof(Native.PatchOptions) }, { "mcon_patch_info", typeof(Native.PatchInfo) },
            { "mcon_patch_repair_info", typeof(Native.PatchRepairInfo) },
            { "mcon_polyline", typeof(Native.PolylineDesc) }, { "mcon_vertex_field", typeof(Native.VertexField) },
            { "mcon_library_entry_desc", typeof(Native.EntryDesc) }, { "mcon_retrieval_options", typeof(Native.RetrievalOptions) },
            { "mcon_patch_frame", typeof(Native.PatchFrame) }, { "mcon_map_options", typeof(Native.MapOptions) },
            { "mcon_cross_field_options", typeof(Native.CrossFieldOptions) }, { "mcon_surface_point", typeof(SurfacePoint) },
            { "mcon_singularity", typeof(Singularity) }, { "mcon_library_info", typeof(LibraryInfo) },
            { "mcon_library_entry_info", typeof(EntryInfo) }, { "mcon_map_info", typeof(MapInfo) },
            { "mcon_mesh_orientation_info", typeof(Native.MeshOrientationInfo) },
            { "mcon_guide_cut_options", typeof(Native.GuideCutOptions) }, { "mcon_cut_mesh_info", typeof(CutMeshInfo) },
        };
        var probe = new System.Text.StringBuilder("#include <stddef.h>\n#include <stdio.h>\n#include \"macrocon/macrocon.h\"\nint main(void) {\n");
        var expected = new List<string>();
        foreach (var kv in types)
        {
            probe.Append($"  printf(\"{kv.Key} %zu\\n\", sizeof({kv.Key}));\n");
            expected.Add(kv.Key + " " + Marshal.SizeOf(kv.Value));
            foreach (var f in kv.Value.GetFields(System.Reflection.BindingFlags.Instance | System.Reflection.BindingFlags.Public))
            {
                string snake = System.Text.RegularExpressions.Regex.Replace(f.Name, "(?<=[a-z0-9])([A-Z])", "_$1").ToLowerInvariant();
                // C arrays (double up[3]) mirrored as three fields NameX, NameY, NameZ: their elements.
                var element = System.Text.RegularExpressions.Regex.Match(snake, "^(.+)_([xyz])$");
                if (element.Success) snake = element.Groups[1].Value + "[" + "xyz".IndexOf(element.Groups[2].Value[0]) + "]";
                string[] notInC = { "b0", "b1", "b2" };  // SurfacePoint's barycentric, checked by sizeof
                if (Array.IndexOf(notInC, snake) >= 0) continue;
                probe.Append($"  printf(\"{kv.Key}.{snake} %zu\\n\", offsetof({kv.Key}, {snake}));\n");
                expected.Add(kv.Key + "." + snake + " " + (long)Marshal.OffsetOf(kv.Value, f.Name));
            }
        }
        probe.Append("  return 0;\n}\n");
        string dir = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "macrocon-cs-layout-" + System.Diagnostics.Process.GetCurrentProcess().Id);
        System.IO.Directory.CreateDirectory(dir);
        try
        {
            System.IO.File.WriteAllText(System.IO.Path.Combine(dir, "layout.c"), probe.ToString());
            Check(Shell("cc", $"-std=c99 -I \"{include}\" layout.c -o layout", dir) != null, "compiling the probe");
            var measured = Shell(System.IO.Path.Combine(dir, "layout"), "", dir).TrimEnd('\n').Split('\n');
            Check(measured.Length == expected.Count && expected.Count > 100, "probe lines: " + measured.Length + " vs " + expected.Count);
            for (int i = 0; i < measured.Length; ++i) Check(measured[i] == expected[i], "C says " + measured[i] + ", C# " + expected[i]);
        }
        finally
        {
            System.IO.Directory.Delete(dir, true);
        }
    }

    static string Shell(string exe, string args, string dir)
    {
        var psi = new System.Diagnostics.ProcessStartInfo(exe, args) { WorkingDirectory = dir, UseShellExecute = false, RedirectStandardOutput = true };
        using (var p = System.Diagnostics.Process.Start(psi))
        {
            string output = p.StandardOutput.ReadToEnd();
            p.WaitForExit();
            return p.ExitCode == 0 ? output : null;
        }
    }

    // No tuple deconstruction (`var (a, b) = ...`) anywhere here: mcs 6.8 silently drops a lambda that
    // contains one (which hid most of this runner's tests before) or crashes when a lambda captures
    // a deconstructed variable. The runner also checks how many tests ran.
    const int ExpectedTests = 27;

    // Mesh.ClosestPoints / Patch.ClosestPoints: distances and feet of points above a grid; host
    // units on a patch; a ragged array and a NaN are refused.
    static void TestClosestPoints()
    {
        var g = Grid(11);  // [0, 1]^2, spacing 0.1
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, g.Item1, g.Item2))
        {
            var c = m.ClosestPoints(new double[] { 0.25, 0.35, 0.2, 1.4, 0.5, 0.0 });
            Check(c.Triangles.Length == 2, "two points");
            Check(Math.Abs(c.Distances[0] - 0.2) < 1e-12 && Math.Abs(c.Distances[1] - 0.4) < 1e-12,
                  "distances " + c.Distances[0] + ", " + c.Distances[1]);
            Check(Math.Abs(c.Barycentric[0] + c.Barycentric[1] + c.Barycentric[2] - 1) < 1e-12, "weights sum to 1");
            using (var patch = Patch.Extract(m, 60, 0.3))
            {
                var p = patch.ClosestPoints(new double[] { 0.5, 0.55, -0.25 });
                Check(Math.Abs(p.Distances[0] - 0.25) < 1e-9, "host units on the patch: " + p.Distances[0]);
                Check(p.Triangles[0] < patch.TriangleCount, "a patch triangle");
                // Geodesic distances: on the plane, the normalized distance from the center vertex (up
                // to the heat method's error on this coarse disk, 3 edges per radius).
                var xyz = patch.Positions();
                uint centre = 0;
                double best = double.MaxValue, worst = 0;
                for (uint v = 0; v < patch.VertexCount; ++v)
                {
                    double r = Math.Sqrt(xyz[3 * v] * xyz[3 * v] + xyz[3 * v + 1] * xyz[3 * v + 1] + xyz[3 * v + 2] * xyz[3 * v + 2]);
                    if (r < best) { best = r; centre = v; }
                }
                var dv = patch.DistanceFromVertices(new uint[] { centre });
                for (uint v = 0; v < patch.VertexCount; ++v)
                {
                    double r = Math.Sqrt(xyz[3 * v] * xyz[3 * v] + xyz[3 * v + 1] * xyz[3 * v + 1] + xyz[3 * v + 2] * xyz[3 * v + 2]);
                    worst = Math.Max(worst, Math.Abs(dv[v] - r));
                }
                Check(dv[centre] == 0 && worst < 0.15, "distance from the center vertex, error " + worst);
                var onTri = patch.DistanceFromPoint(new SurfacePoint(0, 1.0 / 3, 1.0 / 3, 1.0 / 3));
                Check(onTri.Length == patch.VertexCount && onTri[0] >= 0, "distance from a point");
                var bad = Expect<MacroconException>(() => patch.DistanceFromVertices(new uint[] { (uint)patch.VertexCount }));
                Check(bad.Status == Status.InvalidArgument, "a vertex outside the patch: " + bad.Message);
            }
            Expect<ArgumentException>(() => m.ClosestPoints(new double[] { 1, 2 }));
            var e = Expect<MacroconException>(() => m.ClosestPoints(new double[] { 0, double.NaN, 0 }));
            Check(e.Status == Status.NonFinite && e.Message.Contains("coordinate 1 of point 0"), "NaN named: " + e.Message);
        }
    }

    // The log callback receives the status and the message of the exception (mesh and patch
    // errors of the context); other contexts do not log; a disposed context drops late messages.
    static void TestLog()
    {
        var got = new List<(Status S, string M)>();
        var r = Grid(5); var p = r.Item1; var t = r.Item2;
        t[5] = 999;  // out of range
        using (var ctx = new Context(2, (s, m) => { lock (got) got.Add((s, m)); }))
        {
            var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, t));
            Check(e.Status == Status.IndexOutOfRange, "status");
            Check(got.Count == 1, "one message, got " + got.Count);
            Check(got[0].S == Status.IndexOutOfRange, "logged status " + got[0].S);
            Check(got[0].M.Contains("999"), "logged message names the index: " + got[0].M);
            Check(e.Message == e.Status + ": " + got[0].M, "logged text equals the exception's: " + e.Message + " | " + got[0].M);
            Check(ctx.LogExceptions.Count == 0, "no callback exceptions");
            var g = Grid(11);
            using (var m = new Mesh(ctx, g.Item1, g.Item2))
            {
                Check(got.Count == 1, "a successful call logs nothing");
                var pe = Expect<MacroconException>(() => Patch.Extract(m, 60, -1));
                Check(got.Count == 2 && got[1].S == pe.Status && pe.Message == pe.Status + ": " + got[1].M, "patch error logged");
            }
            using (var plain = new Context(2))
                Expect<InvalidMeshException>(() => new Mesh(plain, p, t));
            Check(got.Count == 2, "another context does not log");
        }
        // The mesh outlives its context's handle (the native mesh keeps the native context alive):
        // its errors must neither crash nor reach the callback that was unregistered.
        var g2 = Grid(11);
        Mesh orphan;
        using (var ctx2 = new Context(2, (s, m) => { lock (got) got.Add((s, m)); })) orphan = new Mesh(ctx2, g2.Item1, g2.Item2);
        GC.Collect(); GC.WaitForPendingFinalizers();
        Expect<MacroconException>(() => Patch.Extract(orphan, 60, -1));
        Check(got.Count == 2, "messages after the context's disposal are dropped, got " + got.Count);
        orphan.Dispose();
    }

    // A throwing log callback: nothing crosses into native code, the original error surfaces,
    // the callback's exception is kept, and the context keeps working.
    static void TestLogThrows()
    {
        int calls = 0;
        var r = Grid(5); var p = r.Item1; var t = r.Item2;
        t[5] = 999;
        using (var ctx = new Context(2, (s, m) => { ++calls; throw new InvalidOperationException("logger is broken"); }))
        {
            var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, t));
            Check(e.Status == Status.IndexOutOfRange && e.Message.Contains("999"), "original error: " + e.Message);
            Check(calls == 1, "called once");
            Check(ctx.LogExceptions.Count == 1 && ctx.LogExceptions[0] is InvalidOperationException &&
                  ctx.LogExceptions[0].Message == "logger is broken", "callback exception kept");
            Expect<InvalidMeshException>(() => new Mesh(ctx, p, t));
            Check(calls == 2 && ctx.LogExceptions.Count == 2, "second failure");
            var g = Grid(5);
            using (var m = new Mesh(ctx, g.Item1, g.Item2)) Check(m.Counts.Vertices == 25, "context still works");
        }
    }

    // A vendor's interleaved vertex record (Sequential: the layout of the equivalent C struct).
    [StructLayout(LayoutKind.Sequential)]
    struct Vertex
    {
        public uint Id; public double X, Y, Z; public float Nx, Ny, Nz; public int Label0, Label1; public double W0, W1;
    }

    static readonly int VertexSize = Marshal.SizeOf(typeof(Vertex));
    static int OffsetOf(string field) => Marshal.OffsetOf(typeof(Vertex), field).ToInt32();
    // Spans cannot be captured by the Expect lambdas: each makes its own view of the array.
    static ReadOnlySpan<byte> Bytes(Vertex[] r) => MemoryMarshal.AsBytes(new ReadOnlySpan<Vertex>(r));
    static ReadOnlySpan<byte> Bytes(double[] d) => MemoryMarshal.AsBytes(new ReadOnlySpan<double>(d));

    // Records around packed xyz (3 per vertex); everything else is junk that must never be read as
    // a coordinate (NaN would fail the mesh, a label pattern would change the results).
    static Vertex[] Records(double[] xyz)
    {
        var r = new Vertex[xyz.Length / 3];
        for (int v = 0; v < r.Length; ++v)
            r[v] = new Vertex { Id = 0xFFFFFFFFu, X = xyz[3 * v], Y = xyz[3 * v + 1], Z = xyz[3 * v + 2], Nx = float.NaN, Ny = float.NaN,
                                Nz = float.NaN, Label0 = v % 3, Label1 = v % 5, W0 = xyz[3 * v] * xyz[3 * v], W1 = 1 - xyz[3 * v + 1] };
        return r;
    }

    static bool SameBits(double[] a, double[] b)
    {
        if (a.Length != b.Length) return false;
        for (int i = 0; i < a.Length; ++i) if (BitConverter.DoubleToInt64Bits(a[i]) != BitConverter.DoubleToInt64Bits(b[i])) return false;
        return true;
    }

    static bool Same<T>(T[] a, T[] b) where T : IEquatable<T>
    {
        if (a.Length != b.Length) return false;
        for (int i = 0; i < a.Length; ++i) if (!a[i].Equals(b[i])) return false;
        return true;
    }

    static void SamePatch(Patch a, Patch b, string what)
    {
        Check(SameBits(a.Positions(), b.Positions()) && SameBits(a.Uv(), b.Uv()) && Same(a.Triangles(), b.Triangles()), what + ": mesh");
        var ha = a.HostVertices(); var hb = b.HostVertices();
        Check(Same(ha.V0, hb.V0) && Same(ha.V1, hb.V1) && SameBits(ha.T, hb.T) && Same(a.HostTriangles(), b.HostTriangles()), what + ": host");
        Check(SameBits(a.Descriptors(Descriptor.Curv9), b.Descriptors(Descriptor.Curv9)), what + ": descriptors");
    }

    // int[] and long[] triangles (Unity's int[]): the same meshes and patches bit for bit as uint[],
    // negative indices throw IndexOutOfRange; float[] fields transfer like the widened doubles
    static void TestIndexFormats()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        var ti = Array.ConvertAll(t, v => (int)v);
        var tl = Array.ConvertAll(t, v => (long)v);
        using (var ctx = new Context())
        using (var mu = new Mesh(ctx, p, t))
        using (var mi = new Mesh(ctx, p, ti))
        using (var ml = new Mesh(ctx, p, tl))
        using (var mf = new Mesh(ctx, Array.ConvertAll(p, v => (float)v), ti))
        using (var target = Patch.Extract(mu, 21 * 41 + 20, 0.25))
        using (var fromInt = Patch.Extract(mi, 21 * 41 + 20, 0.25))
        using (var fromLong = Patch.Extract(ml, 21 * 41 + 20, 0.25))
        {
            Check(Same(mu.Triangles(), mi.Triangles()) && Same(mu.Triangles(), ml.Triangles()), "mesh triangles");
            Check(mf.Counts.Vertices == 41 * 41 && mf.Counts.Triangles == t.Length / 3, "float positions, int indices");
            SamePatch(target, fromInt, "extract from int[] mesh");
            SamePatch(target, fromLong, "extract from long[] mesh");
            var tt = target.Triangles();
            using (var su = Patch.FromArrays(ctx, target.Positions(), tt, target.CenterPatchTriangle, target.CenterBarycentric,
                                             target.Center, target.Radius))
            using (var si = Patch.FromArrays(ctx, target.Positions(), Array.ConvertAll(tt, v => (int)v), target.CenterPatchTriangle,
                                             target.CenterBarycentric, target.Center, target.Radius))
            using (var sl = Patch.FromArrays(ctx, target.Positions(), Array.ConvertAll(tt, v => (long)v), target.CenterPatchTriangle,
                                             target.CenterBarycentric, target.Center, target.Radius))
            {
                SamePatch(su, si, "from arrays, int[]");
                SamePatch(su, sl, "from arrays, long[]");
                using (var map = Map.Compute(si, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30 }))
                {
                    var spos = su.Positions();
                    var f32 = Array.ConvertAll(spos, v => (float)v);
                    float[] moved32 = map.TransferField(FieldKind.Vector3, 3, f32);
                    double[] widened = map.TransferField(FieldKind.Vector3, 3, Array.ConvertAll(f32, v => (double)v));
                    double[] full = map.TransferField(FieldKind.Vector3, 3, spos);
                    Check(moved32.Length == widened.Length, "float transfer size");
                    for (int i = 0; i < moved32.Length; ++i)
                    {
                        Check(moved32[i] == (float)widened[i], "float transfer = rounded double transfer of the widened values");
                        Near(moved32[i], full[i], 1e-5, "float transfer near the double transfer");
                    }
                    Expect<ArgumentException>(() => map.TransferField(FieldKind.Scalar, 1, new float[3]));
                    Check(Expect<MacroconException>(() => map.TransferField(FieldKind.Vector3, 2, new float[2 * su.VertexCount])).Status
                          == Status.InvalidArgument, "float vector3 needs 3");
                }
            }
            var bad = (int[])ti.Clone();
            bad[3 * 3 + 1] = -1;
            var e = Expect<InvalidMeshException>(() => new Mesh(ctx, p, bad));
            Check(e.Status == Status.IndexOutOfRange && e.Message.Contains("triangle 3") && e.Message.Contains("-1"), "negative int: " + e.Message);
            var badLong = (long[])tl.Clone();
            badLong[5] = 1L << 33;
            e = Expect<InvalidMeshException>(() => Patch.FromArrays(ctx, p, badLong, 0));
            Check(e.Status == Status.IndexOutOfRange && e.Message.Contains((1L << 33).ToString()), "too large long: " + e.Message);
            Expect<ArgumentException>(() => new Mesh(ctx, p, new int[4]));
            // The interleaved constructor with int[] equals the uint[] one.
            var recs = Records(p);
            using (var a = new Mesh(ctx, Bytes(recs), OffsetOf("X"), VertexSize, p.Length / 3, true, t))
            using (var b = new Mesh(ctx, Bytes(recs), OffsetOf("X"), VertexSize, p.Length / 3, true, ti))
                Check(Same(a.Triangles(), b.Triangles()) && Same(a.Triangles(), mu.Triangles()), "interleaved, int[]");
        }
    }

    // interleaved vertex buffers: meshes equal the packed ones bit for bit; bad layouts throw
    static void TestInterleavedMesh()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        int n = p.Length / 3, x = OffsetOf("X");
        var recs = Records(p);
        Check(VertexSize == 72 && x == 8 && Bytes(recs).Length == 72 * n, "record layout");
        // floats: 5 per vertex, the position after the first
        var pf = Array.ConvertAll(p, v => (float)v);
        var f5 = new float[5 * n];
        for (int v = 0; v < n; ++v) { f5[5 * v] = float.NaN; f5[5 * v + 4] = float.NaN; for (int k = 0; k < 3; ++k) f5[5 * v + 1 + k] = pf[3 * v + k]; }
        using (var ctx = new Context(2))
        using (var packed = new Mesh(ctx, p, t))
        using (var strided = new Mesh(ctx, Bytes(recs), x, VertexSize, n, true, t))
        using (var packedF = new Mesh(ctx, new ReadOnlySpan<float>(pf), t))
        using (var stridedF = new Mesh(ctx, MemoryMarshal.AsBytes(new ReadOnlySpan<float>(f5)), 4, 20, n, false, t))
        {
            Check(strided.Counts.Equals(packed.Counts) && stridedF.Counts.Equals(packed.Counts), "counts");
            foreach (var c in new[] { 20 * 41 + 20, 14 * 41 + 28 })
            {
                using (var a = Patch.Extract(packed, (uint)c, 0.22))
                using (var b = Patch.Extract(strided, (uint)c, 0.22)) SamePatch(a, b, "double records");
                using (var a = Patch.Extract(packedF, (uint)c, 0.22))
                using (var b = Patch.Extract(stridedF, (uint)c, 0.22)) SamePatch(a, b, "float records");
            }
            // Bad layouts: ArgumentException before the call, nothing reaches the library.
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, 0, n, true, t));              // stride 0
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, -72, n, true, t));            // negative stride
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), -8, VertexSize, n, true, t));    // negative offset
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), 56, VertexSize, n, true, t));    // 56 + 24 > 72
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, 16, n, true, t));             // stride < a position
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), 4, VertexSize, n, true, t));     // offset not a multiple of 8
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, 36, n, true, t).Dispose());   // stride not a multiple of 8
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, VertexSize, n + 1, true, t)); // past the buffer
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, VertexSize, -1, true, t));
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs).Slice(1), x, VertexSize, n - 1, true, t)); // misaligned start
            Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), x, VertexSize, n, true, new uint[] { 0, 1 }));
            var e = Expect<ArgumentException>(() => new Mesh(ctx, Bytes(recs), 56, VertexSize, n, true, t));
            Check(e.Message.Contains("offset 56") && e.Message.Contains("stride of 72"), "message names offset and stride: " + e.Message);
            // A valid layout with bad content still gets the library's status (NaN junk read as x).
            Check(Expect<InvalidMeshException>(() => new Mesh(ctx, MemoryMarshal.AsBytes(new ReadOnlySpan<float>(f5)), 0, 20, n, false, t))
                  .Status == Status.NonFinite, "junk is read only when asked for");
        }
    }

    // interleaved fields and descriptors: library, query and transfer equal the packed ones
    static void TestInterleavedFields()
    {
        var r = Bumpy(41); var p = r.Item1; var t = r.Item2;
        int w0 = OffsetOf("W0"), l0 = OffsetOf("Label0");
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, p, t))
        {
            var ps = Patches(m);
            // Descriptors (mean curvature at 3 scales) in column 2..4 of a 6-column double table.
            Func<Patch, double[]> packedDesc = q =>
            {
                var c9 = q.Descriptors(Descriptor.Curv9); var d = new double[3 * q.VertexCount];
                for (int v = 0; v < q.VertexCount; ++v) for (int k = 0; k < 3; ++k) d[3 * v + k] = c9[9 * v + 1 + 3 * k];
                return d;
            };
            Func<Patch, double[]> table = q =>
            {
                var d = packedDesc(q); var tb = new double[6 * q.VertexCount];
                for (int v = 0; v < q.VertexCount; ++v) { tb[6 * v] = double.NaN; tb[6 * v + 1] = -1; tb[6 * v + 5] = double.NaN; for (int k = 0; k < 3; ++k) tb[6 * v + 2 + k] = d[3 * v + k]; }
                return tb;
            };
            Func<bool, ConstraintLibrary> build = strided =>
            {
                var lib = new ConstraintLibrary(ctx);
                foreach (var q in ps)
                {
                    var rec = Records(q.Positions()); int n = rec.Length;
                    var weights = new double[2 * n]; var labels = new int[2 * n];
                    for (int v = 0; v < n; ++v) { weights[2 * v] = rec[v].W0; weights[2 * v + 1] = rec[v].W1; labels[2 * v] = rec[v].Label0; labels[2 * v + 1] = rec[v].Label1; }
                    var e = strided
                        ? new EntryDesc { Name = "e", Fields = new[] {
                              Field.FromRecords("weights", FieldKind.Scalar, 2, rec, w0, VertexSize),
                              Field.FromRecords("part", FieldKind.IntegerLabel, 2, rec, l0, VertexSize) },
                              DescriptorRecords = table(q), DescriptorOffset = 16, DescriptorStride = 48, DescriptorDimension = 3 }
                        : new EntryDesc { Name = "e", Fields = new[] {
                              new Field { Name = "weights", Kind = FieldKind.Scalar, Dimension = 2, Values = weights },
                              new Field { Name = "part", Kind = FieldKind.IntegerLabel, Dimension = 2, Labels = labels } },
                              Descriptors = packedDesc(q), DescriptorDimension = 3 };
                    lib.AddEntry(q, e);
                }
                lib.BuildRetrieval(new RetrievalSettings { Descriptor = RetrievalDescriptor.Custom, VocabularySize = 8, Seed = 5 });
                return lib;
            };
            using (var packed = build(false))
            using (var strided = build(true))
            {
                Check(Same(packed.SaveMemory(), strided.SaveMemory()), "library bytes equal");
                var f = strided.GetEntryField(1, 1);
                Check(f.Kind == FieldKind.IntegerLabel && f.Labels[2 * 7] == 7 % 3 && f.Labels[2 * 7 + 1] == 7 % 5, "labels read in place");
                for (int k = 0; k < ps.Length; ++k)
                {
                    var a = packed.QueryDescriptors(ps[k], packedDesc(ps[k]), 3, 3);
                    var tb = table(ps[k]);
                    var b = packed.QueryDescriptors(ps[k], MemoryMarshal.AsBytes(new ReadOnlySpan<double>(tb)), 16, 48, 3, 3);
                    Check(a.Indices[0] == k && Same(a.Ids, b.Ids) && Same(a.Indices, b.Indices) && SameBits(a.Distances, b.Distances), "query " + k);
                }
                var tb0 = table(ps[0]);
                Expect<ArgumentException>(() => packed.QueryDescriptors(ps[0], Bytes(tb0), 32, 48, 3, 3));  // 32 + 24 > 48
                Expect<ArgumentException>(() => packed.QueryDescriptors(ps[0], Bytes(tb0), 16, 0, 3, 3));
                Expect<ArgumentException>(() => packed.QueryDescriptors(ps[0], Bytes(tb0), 12, 48, 3, 3)); // not a multiple of 8
                Expect<ArgumentException>(() => packed.QueryDescriptors(ps[0], Bytes(tb0).Slice(0, 8 * tb0.Length - 16), 16, 48, 3, 3)); // last row cut
            }
            // Bad field layouts throw ArgumentException before the call; the library stays empty.
            using (var lib = new ConstraintLibrary(ctx))
            {
                var q = ps[0]; var rec = Records(q.Positions());
                Action<Field> add = fld => lib.AddEntry(q, new EntryDesc { Fields = new[] { fld } });
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 2, rec, 64, VertexSize)));   // 64 + 16 > 72
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 2, rec, w0, 0)));
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 2, rec, w0, -VertexSize)));
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 2, rec, 4, VertexSize)));    // misaligned double
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 2, new Vertex[rec.Length - 1], w0, VertexSize)));
                Expect<ArgumentException>(() => add(Field.FromRecords("w", FieldKind.Scalar, 1, new string[3 * rec.Length], 0, 8))); // not blittable
                var both = Field.FromRecords("w", FieldKind.Scalar, 2, rec, w0, VertexSize); both.Values = new double[2 * rec.Length];
                Expect<ArgumentException>(() => add(both));
                Expect<ArgumentException>(() => lib.AddEntry(q, new EntryDesc { DescriptorRecords = table(q), DescriptorOffset = 32,
                                                                                DescriptorStride = 48, DescriptorDimension = 3 }));
                Check(lib.Count == 0, "nothing was added");
            }
            foreach (var q in ps) q.Dispose();
        }
        // Field transfer: records in, the same doubles and labels out as from packed arrays.
        using (var ctx = new Context(2))
        using (var m = new Mesh(ctx, p, t))
        using (var target = Patch.Extract(m, 21 * 41 + 20, 0.25))
        using (var source = Patch.FromArrays(ctx, target.Positions(), target.Triangles(), target.CenterPatchTriangle,
                                             target.CenterBarycentric, target.Center, target.Radius))
        using (var map = Map.Compute(source, target, new MapSettings { Seed = 3, AlignmentSamples = 400, MaxIterations = 30 }))
        {
            var spos = source.Positions();
            var rec = Records(spos); int n = rec.Length;
            var labels = new int[2 * n]; var weights = new double[2 * n];
            for (int v = 0; v < n; ++v) { labels[2 * v] = rec[v].Label0; labels[2 * v + 1] = rec[v].Label1; weights[2 * v] = rec[v].W0; weights[2 * v + 1] = rec[v].W1; }
            Check(SameBits(map.TransferField(FieldKind.Vector3, 3, Bytes(rec), OffsetOf("X"), VertexSize), map.TransferField(FieldKind.Vector3, 3, spos)),
                  "vector field from records");
            Check(SameBits(map.TransferField(FieldKind.Scalar, 2, Bytes(rec), w0, VertexSize), map.TransferField(FieldKind.Scalar, 2, weights)),
                  "scalar field from records");
            Check(Same(map.TransferLabels(2, Bytes(rec), l0, VertexSize, -3), map.TransferLabels(2, labels, -3)), "labels from records");
            Expect<ArgumentException>(() => map.TransferField(FieldKind.Vector3, 3, Bytes(rec), 56, VertexSize));  // 56 + 24 > 72
            Expect<ArgumentException>(() => map.TransferField(FieldKind.Vector3, 3, Bytes(rec), OffsetOf("X"), 0));
            Expect<ArgumentException>(() => map.TransferField(FieldKind.Vector3, 3, Bytes(rec).Slice(0, Bytes(rec).Length - 72), OffsetOf("X"), VertexSize));
            Expect<ArgumentException>(() => map.TransferLabels(2, Bytes(rec), l0, 6));
            Expect<ArgumentException>(() => map.TransferLabels(2, Bytes(rec), 2, VertexSize));  // not a multiple of 4
        }
    }

    static int Main()
    {
        Run("version and ABI", Test0);
        Run("mesh from doubles and floats", Test1);
        Run("invalid mesh throws with status and message", Test2);
        Run("MeshFlags.ValidateLocally: defects away from the patch", TestValidateLocally);
        Run("Patch.Extract(repair: true): zero-area triangles and pinched vertices repaired", TestRepair);
        Run("patch extraction", Test3);
        Run("closest points and geodesic distances on a mesh and a patch", TestClosestPoints);
        Run("patch extraction at a triangle + barycentric, Python's arguments", TestExtractAtTriangle);
        Run("progress cancels and callback exceptions propagate", Test4);
        Run("library: entries round trip through every getter", Test5);
        Run("library: save, open, bytes, remove, find, merge", Test6);
        Run("library: descriptor at creation, name, description", TestLibraryStrings);
        Run("library: an entry stores its up direction", TestEntryUp);
        Run("library: retrieval finds each entry itself; cancel leaves it unchanged", Test7);
        Run("library: bad input, forged bytes, disposed handles", Test8);
        Run("map: from arrays, compute, correspondences, transfer, cross field", Test9);
        Run("cut mesh: guides become edge chains; carry, cross field, QuadWild files, bad arguments", TestCutMesh);
        Run("map: forced orientation and the evidence of the automatic call", TestOrientation);
        Run("map: guidance channels decide what the geometry cannot", TestGuidance);
        Run("winding: reversed host triangles are repaired and reported", TestWinding);
        Run("struct layouts match macrocon.h", TestLayout);
        Run("log callback gets status and message of errors", TestLog);
        Run("throwing log callback: error surfaces, nothing crosses into native code", TestLogThrows);
        Run("interleaved vertex buffers: meshes equal packed; bad offset/stride throw", TestInterleavedMesh);
        Run("interleaved fields and descriptors: library, query, transfer equal packed", TestInterleavedFields);
        Run("int[] and long[] triangles equal uint[]; float[] fields transfer like doubles", TestIndexFormats);
        Run("heavy parallel work then shutdown", Test10);
        GC.Collect();
        GC.WaitForPendingFinalizers();
        Library.Shutdown();
        if (passed + failed != ExpectedTests)
        {
            failed++;
            Console.WriteLine($"FAIL runner: {passed + failed - 1} tests ran, {ExpectedTests} expected");
        }
        Console.WriteLine($"{passed} passed, {failed} failed");
        return failed == 0 ? 0 : 1;
    }
}
