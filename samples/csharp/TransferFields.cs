// Macrocon sample (C# binding, Mono): the integration pattern of a DCC plugin.
//
//   mono TransferFields.exe LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT.ply
//
//  1. the host mesh (arrays; a plugin takes them from its host application) -> Mesh
//  2. the user's region (a vertex + a geodesic radius) -> a normalized disk Patch
//  3. query the constraint library for the three most similar macro constraints
//  4. re-embed the best one onto the region (Map.Compute)
//  5. transfer its per-vertex fields (uv, skin weights, colour, labels) and guides
//  6. write the fields back onto the host vertices (here a PLY file; a plugin sets attributes)
//
// Errors are MacroconException (Status + the SDK's message); NotADiskException means "try a smaller
// radius". Every object is IDisposable (using blocks); Library.Shutdown() runs once at the end
// (the binding's exit hook also disposes leftovers and shuts down, so a crash path exits cleanly).
// Build: mcs -unsafe -langversion:7.2 -out:TransferFields.exe bindings/csharp/*.cs samples/csharp/TransferFields.cs
// Run with LD_LIBRARY_PATH pointing at libmacrocon.so.
using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.IO.Compression;
using System.Text;
using Macrocon;

public static class TransferFields
{
    // OBJ (optionally .gz) -> flat float positions and uint triangles; polygons are fanned.
    static (float[] Positions, uint[] Triangles) LoadObj(string path)
    {
        var positions = new List<float>();
        var triangles = new List<uint>();
        Stream stream = File.OpenRead(path);
        if (path.EndsWith(".gz", StringComparison.Ordinal)) stream = new GZipStream(stream, CompressionMode.Decompress);
        using (var reader = new StreamReader(stream))
        {
            string line;
            while ((line = reader.ReadLine()) != null)
            {
                var w = line.Split((char[])null, StringSplitOptions.RemoveEmptyEntries);
                if (w.Length == 0) continue;
                if (w[0] == "v")
                    for (int k = 1; k <= 3; ++k) positions.Add(float.Parse(w[k], CultureInfo.InvariantCulture));
                else if (w[0] == "f")
                {
                    var c = new uint[w.Length - 1];
                    for (int k = 1; k < w.Length; ++k)
                    {
                        int v = int.Parse(w[k].Split('/')[0], CultureInfo.InvariantCulture);
                        c[k - 1] = (uint)(v > 0 ? v - 1 : positions.Count / 3 + v);
                    }
                    for (int k = 1; k + 1 < c.Length; ++k) { triangles.Add(c[0]); triangles.Add(c[k]); triangles.Add(c[k + 1]); }
                }
            }
        }
        return (positions.ToArray(), triangles.ToArray());
    }

    static void WritePly(string path, float[] positions, uint[] triangles, List<(string Name, int Dim, double[] Values)> attributes)
    {
        int n = positions.Length / 3;
        var inv = CultureInfo.InvariantCulture;
        using (var f = new StreamWriter(path, false, new UTF8Encoding(false)))
        {
            f.NewLine = "\n";
            f.WriteLine("ply\nformat ascii 1.0\ncomment written by the Macrocon C# sample");
            f.WriteLine($"element vertex {n}\nproperty float x\nproperty float y\nproperty float z");
            foreach (var a in attributes)
            {
                if (a.Name == "color" && a.Dim == 3) f.WriteLine("property uchar red\nproperty uchar green\nproperty uchar blue");
                else if (a.Dim == 1) f.WriteLine($"property float {a.Name}");
                else for (int c = 0; c < a.Dim; ++c) f.WriteLine($"property float {a.Name}_{c}");
            }
            f.WriteLine($"element face {triangles.Length / 3}\nproperty list uchar int vertex_indices\nend_header");
            var row = new StringBuilder();
            for (int v = 0; v < n; ++v)
            {
                row.Clear();
                row.Append(positions[3 * v].ToString("R", inv)).Append(' ').Append(positions[3 * v + 1].ToString("R", inv))
                   .Append(' ').Append(positions[3 * v + 2].ToString("R", inv));
                foreach (var a in attributes)
                    for (int c = 0; c < a.Dim; ++c)
                    {
                        double x = a.Values[v * a.Dim + c];
                        row.Append(' ');
                        if (a.Name == "color" && a.Dim == 3) row.Append((int)Math.Round(Math.Min(1, Math.Max(0, x)) * 255));
                        else row.Append(x.ToString("R", inv));
                    }
                f.WriteLine(row.ToString());
            }
            for (int t = 0; t < triangles.Length; t += 3) f.WriteLine($"3 {triangles[t]} {triangles[t + 1]} {triangles[t + 2]}");
        }
    }

    public static int Main(string[] args)
    {
        if (args.Length != 5)
        {
            Console.Error.WriteLine("usage: TransferFields.exe LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT.ply");
            return 2;
        }
        var inv = CultureInfo.InvariantCulture;
        uint centerVertex = uint.Parse(args[2], inv);
        double radius = double.Parse(args[3], inv);
        try
        {
            Library.CheckAbi();  // the native library must have this binding's ABI major version
            var (positions, triangles) = LoadObj(args[1]);
            int hostVertices = positions.Length / 3;
            using (var context = new Context())
            using (var library = ConstraintLibrary.Open(context, args[0]))
            using (var host = new Mesh(context, positions, triangles))
            using (var region = Patch.Extract(host, centerVertex, radius))
            {
                Console.WriteLine($"region: vertex {centerVertex}, radius {radius.ToString(inv)}: {region.VertexCount} vertices");
                var found = library.Query(region, 3);
                for (int i = 0; i < found.Count; ++i)
                {
                    int e = (int)found.Indices[i];
                    Console.WriteLine($"suggestion {i + 1}: id {found.Ids[i]}, class {library.GetEntryString(e, EntryString.ClassLabel)}, " +
                                      $"distance {found.Distances[i].ToString("F4", inv)}: {library.GetEntryString(e, EntryString.Name)}");
                }
                int best = (int)found.Indices[0];
                Console.WriteLine($"using entry {found.Ids[0]} by {library.GetEntryString(best, EntryString.Author)}, " +
                                  $"licence {library.GetEntryString(best, EntryString.Licence)}");

                // The entry as a Patch (its arrays, center and frame), then the map onto the region.
                var info = library.GetEntryInfo(best);
                var c = info.Center;
                using (var source = Patch.FromArrays(context, library.GetEntryPositions(best), library.GetEntryTriangles(best),
                                                     c.Face, new[] { c.B0, c.B1, c.B2 },
                                                     new[] { info.SourceOriginX, info.SourceOriginY, info.SourceOriginZ }, info.SourceScale))
                using (var map = Map.Compute(source, region))
                {
                    var m = map.Info;
                    Console.WriteLine($"map: overlap {m.OverlapRatio.ToString("F3", inv)}, matching score {m.MatchingScore.ToString("F3", inv)}, " +
                                      $"{m.Iterations} iterations, {(m.Reflected != 0 ? "mirrored" : "not mirrored")}, {m.FlippedTriangles} flipped triangles");
                    // Region vertices that are host vertices (v0 == v1, t == 0) carry values back.
                    var (v0, v1, t) = region.HostVertices();
                    bool[] outside = map.OutsideMask();
                    var mask = new double[hostVertices];
                    var attributes = new List<(string, int, double[])> { ("macro_mask", 1, mask) };
                    for (int i = 0; i < v0.Length; ++i)
                        if (v0[i] == v1[i] && v0[i] != 0xFFFFFFFFu && t[i] == 0 && !outside[i]) mask[v0[i]] = 1;
                    foreach (var field in library.GetEntryFields(best))
                    {
                        double[] values;
                        if (field.Kind == FieldKind.IntegerLabel)
                        {
                            int[] labels = map.TransferLabels(field.Dimension, field.Labels);  // never blended
                            values = Array.ConvertAll(labels, x => (double)x);
                        }
                        else
                            values = map.TransferField(field.Kind, field.Dimension, field.Values);
                        var hostValues = new double[hostVertices * field.Dimension];
                        for (int i = 0; i < v0.Length; ++i)
                            if (v0[i] == v1[i] && v0[i] != 0xFFFFFFFFu && t[i] == 0 && !outside[i])
                                Array.Copy(values, i * field.Dimension, hostValues, (int)v0[i] * field.Dimension, field.Dimension);
                        attributes.Add((field.Name, field.Dimension, hostValues));
                    }
                    int guides;
                    using (var set = map.TransferPolylines(library.GetEntryPolylines(best)))
                        guides = set.Counts.Polylines;
                    WritePly(args[4], positions, triangles, attributes);
                    int masked = 0;
                    foreach (double x in mask) if (x == 1) ++masked;
                    Console.WriteLine($"transferred {attributes.Count - 1} field(s) onto {masked} host vertices, {guides} guide polyline(s) -> {args[4]}");
                }
            }
        }
        catch (NotADiskException e)
        {
            Console.Error.WriteLine($"TransferFields: the region is not a disk, try a smaller radius: {e.Message}");
            return 1;
        }
        catch (MacroconException e)
        {
            Console.Error.WriteLine($"TransferFields: {e.Message}");
            return 1;
        }
        Library.Shutdown();
        return 0;
    }
}
