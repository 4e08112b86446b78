// Re-embedding maps and constraint transfer (mcon_map_*, mcon_polyline_set_*) for C#.
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;

namespace Macrocon
{
    /// <summary>One term of a map's energy: its name and final unweighted value.</summary>
    public struct EnergyTerm
    {
        public string Name;
        public double Value;
    }

    /// <summary>Map settings; null members keep the library's defaults.</summary>
    public sealed class MapSettings
    {
        public ulong Seed;
        public uint? AlignmentSamples, MaxIterations;
        public bool AllowReflection = true;  // restricts Automatic only
        /// <summary>Automatic, or force one (a "flip" recomputes with the one opposite to Info.Reflected).</summary>
        public MapOrientation Orientation = MapOrientation.Automatic;
        /// <summary>Optional guidance channels: GuidanceDimension values per vertex (packed), for every
        /// source vertex in SourceGuidance and every target vertex in TargetGuidance, that must agree
        /// between corresponding points (painted region ids, landmark distances); each column is
        /// normalized over both patches and scaled by GuidanceWeight. Both null: none.</summary>
        public double[] SourceGuidance, TargetGuidance;
        public int GuidanceDimension;
        public double? GuidanceWeight;
        /// <summary>Gaussian width factor of the refinement pass after the finest level: 0 turns it
        /// off, otherwise in (0, 1].</summary>
        public double? RefineSigmaFactor;
        /// <summary>Both patches sit in one world frame: the similarity-ICP alignment of their host
        /// positions is the rigid start and decides orientation (Info.FrameDecided); needs Automatic.
        /// WorldFrameMirror mirrors the source x -> -x first (a left part onto a right one).</summary>
        public bool UseWorldFrame, WorldFrameMirror;
        /// <summary>With UseWorldFrame: weight (finite, >= 0; 0 = off) of the term keeping each source point near
        /// its 3D closest target point after that alignment; null keeps the SDK default.</summary>
        public double? WorldFrameAnchor;
        /// <summary>Up directions of the source's and the target's hosts (3 numbers each, own coordinates; both or
        /// neither): a prior of the rigid start, so the map is never upside down.</summary>
        public double[] SourceUp, TargetUp;
        /// <summary>Coarse to fine in mesh resolution: the first CoarseStages stages (SDK default 3, 0 = off) run on a
        /// copy of the source coarsened to max(CoarseVertices, n / 4) vertices (default 1000) when the source has at
        /// least 2 * CoarseVertices (Info.CoarseVertices ...); null keeps the SDK default.</summary>
        public uint? CoarseStages, CoarseVertices;
    }

    /// <summary>Polylines re-traced on a target patch (every segment inside one target triangle).</summary>
    public sealed class PolylineSet : IDisposable
    {
        internal readonly PolylineSetHandle Handle;

        internal PolylineSet(PolylineSetHandle handle) { Handle = handle; }

        public (int Polylines, int Points) Counts
        {
            get
            {
                Native.Check(Native.mcon_polyline_set_get_counts(Handle, out UIntPtr n, out UIntPtr p));
                return ((int)n, (int)p);
            }
        }

        /// <summary>Per polyline: point count, closed flag, the input polyline it came from.</summary>
        public (uint[] Sizes, bool[] Closed, uint[] InputPolyline) Polylines()
        {
            int n = Counts.Polylines;
            var sizes = new uint[n]; var closed = new byte[n]; var input = new uint[n];
            Native.Check(Native.mcon_polyline_set_get_polylines(Handle, sizes, closed, input, (UIntPtr)n));
            return (sizes, Array.ConvertAll(closed, c => c != 0), input);
        }

        /// <summary>All points: target triangle, 3 barycentric weights, 3D position in the target's host units.</summary>
        public (uint[] Triangles, double[] Barycentric, double[] Xyz) Points()
        {
            int p = Counts.Points;
            var t = new uint[p]; var b = new double[3 * p]; var x = new double[3 * p];
            Native.Check(Native.mcon_polyline_set_get_points(Handle, t, b, x, (UIntPtr)p));
            return (t, b, x);
        }

        public void Dispose() => Handle.Dispose();
    }

    /// <summary>The re-embedding map Phi from a source patch onto a target patch (locally injective, partial).</summary>
    public sealed class Map : IDisposable
    {
        internal readonly MapHandle Handle;
        private readonly int sourceVertices, targetVertices;

        private Map(MapHandle handle)
        {
            Handle = handle;
            var i = Info;
            sourceVertices = (int)i.SourceVertexCount;
            targetVertices = (int)i.TargetVertexCount;
        }

        public static Map Compute(Patch source, Patch target, MapSettings settings = null, Func<double, bool> progress = null)
        {
            if (source == null) throw new ArgumentNullException(nameof(source));
            if (target == null) throw new ArgumentNullException(nameof(target));
            settings = settings ?? new MapSettings();
            var o = new Native.MapOptions();
            Native.Check(Native.mcon_map_options_init(ref o));
            o.seed = settings.Seed;
            if (settings.AlignmentSamples.HasValue) o.alignment_samples = settings.AlignmentSamples.Value;
            if (settings.MaxIterations.HasValue) o.max_iterations = settings.MaxIterations.Value;
            o.allow_reflection = settings.AllowReflection ? 1u : 0u;
            o.orientation = (uint)settings.Orientation;
            o.use_world_frame = settings.UseWorldFrame ? 1u : 0u;
            o.world_frame_mirror = settings.WorldFrameMirror ? 1u : 0u;
            if (settings.WorldFrameAnchor.HasValue) o.world_frame_anchor = settings.WorldFrameAnchor.Value;
            if ((settings.SourceUp == null) != (settings.TargetUp == null))
                throw new ArgumentException("SourceUp and TargetUp must be given together");
            if (settings.SourceUp != null)
            {
                if (settings.SourceUp.Length != 3 || settings.TargetUp.Length != 3)
                    throw new ArgumentException("SourceUp and TargetUp need 3 components each");
                o.use_up_hints = 1;
                o.source_up_x = settings.SourceUp[0]; o.source_up_y = settings.SourceUp[1]; o.source_up_z = settings.SourceUp[2];
                o.target_up_x = settings.TargetUp[0]; o.target_up_y = settings.TargetUp[1]; o.target_up_z = settings.TargetUp[2];
            }
            if (settings.RefineSigmaFactor.HasValue) o.refine_sigma_factor = settings.RefineSigmaFactor.Value;
            if (settings.CoarseStages.HasValue) o.coarse_stages = settings.CoarseStages.Value;
            if (settings.CoarseVertices.HasValue) o.coarse_vertices = settings.CoarseVertices.Value;
            if ((settings.SourceGuidance == null) != (settings.TargetGuidance == null))
                throw new ArgumentException("SourceGuidance and TargetGuidance must be given together");
            if (settings.SourceGuidance != null)
            {
                int d = settings.GuidanceDimension;
                if (d < 1 || settings.SourceGuidance.Length != (long)d * source.VertexCount ||
                    settings.TargetGuidance.Length != (long)d * target.VertexCount)
                    throw new ArgumentException("guidance needs GuidanceDimension >= 1 values per source and per target vertex (" +
                                                source.VertexCount + " and " + target.VertexCount + " vertices)");
                o.guidance_dimension = checked((uint)d);
                if (settings.GuidanceWeight.HasValue) o.guidance_weight = settings.GuidanceWeight.Value;
            }
            else if (settings.GuidanceDimension != 0)
                throw new ArgumentException("GuidanceDimension without SourceGuidance / TargetGuidance");
            unsafe
            {
                fixed (double* gs = settings.SourceGuidance)
                fixed (double* gt = settings.TargetGuidance)
                using (var scope = new Native.ProgressScope(progress))
                {
                    o.source_guidance = (IntPtr)gs;
                    o.target_guidance = (IntPtr)gt;
                    o.progress = scope.Function;
                    o.progress_user_data = scope.UserData;
                    Status s = Native.mcon_map_compute(source.Handle, target.Handle, ref o, out MapHandle h);
                    scope.Finish(s);
                    return new Map(h);
                }
            }
        }

        public MapInfo Info
        {
            get
            {
                var i = new MapInfo();
                Native.Check(Native.mcon_map_info_init(ref i));
                Native.Check(Native.mcon_map_get_info(Handle, ref i));
                return i;
            }
        }

        /// <summary>The energy terms in evaluation order: name and final unweighted value.</summary>
        public EnergyTerm[] EnergyTerms
        {
            get
            {
                Native.Check(Native.mcon_map_get_energy_term_count(Handle, out uint n));
                var terms = new EnergyTerm[n];
                for (uint k = 0; k < n; ++k)
                {
                    Native.Check(Native.mcon_map_get_energy_term(Handle, k, out IntPtr name, out double value));
                    terms[k] = new EnergyTerm { Name = Marshal.PtrToStringAnsi(name), Value = value };
                }
                return terms;
            }
        }

        /// <summary>Per vertex of the direction's domain: triangle of the other patch (-1 = outside) and 3 weights.</summary>
        public (int[] Triangles, double[] Barycentric) Correspondences(MapDirection direction)
        {
            int n = direction == MapDirection.TargetToSource ? targetVertices : sourceVertices;
            var t = new int[n]; var b = new double[3 * n];
            Native.Check(Native.mcon_map_get_correspondences(Handle, direction, t, b, (UIntPtr)n));
            return (t, b);
        }

        /// <summary>The deformed source disk in the target disk's plane, 2 doubles per source vertex.</summary>
        public double[] Phi()
        {
            var a = new double[2 * sourceVertices];
            Native.Check(Native.mcon_map_get_phi(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        /// <summary>Per target vertex: true if it has no source preimage.</summary>
        public bool[] OutsideMask()
        {
            var m = new byte[targetVertices];
            Native.Check(Native.mcon_map_get_outside_mask(Handle, m, (UIntPtr)m.Length));
            return Array.ConvertAll(m, x => x != 0);
        }

        /// <summary>Source points (triangle + 3 weights each) -> target triangle (0xFFFFFFFF = outside), weights, 3D.</summary>
        public unsafe (uint[] Triangles, double[] Barycentric, double[] Xyz) TransferPoints(ReadOnlySpan<uint> triangles,
                                                                                           ReadOnlySpan<double> barycentric)
        {
            if (barycentric.Length != 3 * triangles.Length) throw new ArgumentException("barycentric must hold 3 weights per point");
            int n = triangles.Length;
            var ot = new uint[n]; var ob = new double[3 * n]; var ox = new double[3 * n];
            fixed (uint* t = &MemoryMarshal.GetReference(triangles))
            fixed (double* b = &MemoryMarshal.GetReference(barycentric))
                Native.Check(Native.mcon_map_transfer_points(Handle, (IntPtr)t, (IntPtr)b, (UIntPtr)n, ot, ob, ox, (UIntPtr)n));
            return (ot, ob, ox);
        }

        /// <summary>Source polylines (e.g. a library entry's) mapped through Phi and re-traced on the target.</summary>
        public PolylineSet TransferPolylines(IReadOnlyList<Polyline> polylines)
        {
            if (polylines == null) throw new ArgumentNullException(nameof(polylines));
            int total = 0;
            foreach (var p in polylines) total += (p ?? throw new ArgumentNullException(nameof(polylines))).Points.Length;
            var t = new uint[total]; var b = new double[3 * total];
            var sizes = new uint[polylines.Count]; var closed = new byte[polylines.Count];
            int k = 0;
            for (int i = 0; i < polylines.Count; ++i)
            {
                sizes[i] = (uint)polylines[i].Points.Length;
                closed[i] = polylines[i].Closed ? (byte)1 : (byte)0;
                foreach (var q in polylines[i].Points)
                {
                    t[k] = q.Face; b[3 * k] = q.B0; b[3 * k + 1] = q.B1; b[3 * k + 2] = q.B2; ++k;
                }
            }
            Native.Check(Native.mcon_map_transfer_polylines(Handle, t, b, (UIntPtr)total, sizes, closed, (UIntPtr)sizes.Length,
                                                            out PolylineSetHandle h));
            return new PolylineSet(h);
        }

        /// <summary>A per-source-vertex field (dimension values per vertex) -> per target vertex; outside gets 0.</summary>
        public unsafe double[] TransferField(FieldKind kind, int dimension, ReadOnlySpan<double> values)
        {
            if (kind == FieldKind.IntegerLabel) throw new ArgumentException("integer labels go through TransferLabels");
            if (dimension < 1 || values.Length != dimension * sourceVertices)
                throw new ArgumentException($"values must hold {dimension} per source vertex ({sourceVertices})");
            var o = new double[dimension * targetVertices];
            fixed (double* v = &MemoryMarshal.GetReference(values))
                Native.Check(Native.mcon_map_transfer_field(Handle, kind, checked((uint)dimension), (IntPtr)v, (UIntPtr)values.Length, o,
                                                            (UIntPtr)o.Length));
            return o;
        }

        /// <summary>The same with float values (Unity): mcon_map_transfer_field_f32, computed in double
        /// and rounded once, so it equals the double overload on the widened values, cast to float.</summary>
        public unsafe float[] TransferField(FieldKind kind, int dimension, ReadOnlySpan<float> values)
        {
            if (kind == FieldKind.IntegerLabel) throw new ArgumentException("integer labels go through TransferLabels");
            if (dimension < 1 || values.Length != dimension * sourceVertices)
                throw new ArgumentException($"values must hold {dimension} per source vertex ({sourceVertices})");
            var o = new float[dimension * targetVertices];
            fixed (float* v = &MemoryMarshal.GetReference(values))
                Native.Check(Native.mcon_map_transfer_field_f32(Handle, kind, checked((uint)dimension), (IntPtr)v, (UIntPtr)values.Length, o,
                                                                (UIntPtr)o.Length));
            return o;
        }

        /// <summary>A field that lives inside interleaved per-source-vertex records: vertex v's
        /// `dimension` doubles start at byte fieldOffset + v * recordStride of recordBytes (e.g.
        /// <c>MemoryMarshal.AsBytes(records.AsSpan())</c>). mcon_map_transfer_field takes packed rows
        /// (no stride), so the binding packs the field once (dimension * source vertices doubles)
        /// and transfers that; the result equals TransferField of the packed values bit for bit.
        /// ArgumentException for a layout that does not fit (see the Mesh interleaved constructor).</summary>
        public double[] TransferField(FieldKind kind, int dimension, ReadOnlySpan<byte> recordBytes, int fieldOffset, int recordStride)
        {
            if (dimension < 1) throw new ArgumentException($"dimension {dimension} must be >= 1");
            Interleaved.Check("recordBytes", recordBytes.Length, fieldOffset, recordStride, sourceVertices, 8 * dimension, 8);
            var packed = new double[dimension * sourceVertices];
            Interleaved.Pack(recordBytes, fieldOffset, recordStride, sourceVertices, 8 * dimension,
                             MemoryMarshal.AsBytes(new Span<double>(packed)));
            return TransferField(kind, dimension, packed);
        }

        /// <summary>Integer labels inside interleaved records (int32, `dimension` per vertex at byte
        /// fieldOffset + v * recordStride), packed once like the TransferField overload.</summary>
        public int[] TransferLabels(int dimension, ReadOnlySpan<byte> recordBytes, int fieldOffset, int recordStride, int outsideLabel = -1)
        {
            if (dimension < 1) throw new ArgumentException($"dimension {dimension} must be >= 1");
            Interleaved.Check("recordBytes", recordBytes.Length, fieldOffset, recordStride, sourceVertices, 4 * dimension, 4);
            var packed = new int[dimension * sourceVertices];
            Interleaved.Pack(recordBytes, fieldOffset, recordStride, sourceVertices, 4 * dimension,
                             MemoryMarshal.AsBytes(new Span<int>(packed)));
            return TransferLabels(dimension, packed, outsideLabel);
        }

        /// <summary>Integer labels, never blended; target vertices outside the overlap get outsideLabel.</summary>
        public unsafe int[] TransferLabels(int dimension, ReadOnlySpan<int> labels, int outsideLabel = -1)
        {
            if (dimension < 1 || labels.Length != dimension * sourceVertices)
                throw new ArgumentException($"labels must hold {dimension} per source vertex ({sourceVertices})");
            var o = new int[dimension * targetVertices];
            fixed (int* v = &MemoryMarshal.GetReference(labels))
                Native.Check(Native.mcon_map_transfer_labels(Handle, checked((uint)dimension), (IntPtr)v, (UIntPtr)labels.Length, outsideLabel, o,
                                                             (UIntPtr)o.Length));
            return o;
        }

        public void Dispose() => Handle.Dispose();
    }
}
