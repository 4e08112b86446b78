// C# binding over the Macrocon C ABI: P/Invoke, one SafeHandle per handle type, IDisposable
// wrappers, exceptions from status codes, arrays and spans in, progress and log callbacks through
// static trampolines (the delegate never moves; the user's callback travels as a GCHandle for
// progress, as a table key for the log, see LogTrampoline).
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;

// The test runner checks the C layout of the internal structs against macrocon.h.
[assembly: System.Runtime.CompilerServices.InternalsVisibleTo("MacroconTests")]

namespace Macrocon
{
    public enum Status
    {
        Ok = 0, Unknown = 1, InvalidArgument = 2, NullPointer = 3, StructSize = 4, OutOfMemory = 5,
        BufferTooSmall = 6, Cancelled = 7, IO = 8, NonFinite = 10, IndexOutOfRange = 11, RepeatedIndex = 12,
        DegenerateTriangle = 13, NonManifoldEdge = 14, NonManifoldVertex = 15, IsolatedVertex = 16,
        EmptyMesh = 17, NonOrientable = 18, NotADisk = 20, Numerical = 21, InvalidLibrary = 30, Unsupported = 31, NotFound = 32,
    }

    public enum Descriptor { Curv9 = 1, MeanCurvature = 2 }

    /// <summary>mcon_field_kind: how a per-vertex field is stored and transferred.</summary>
    public enum FieldKind { Scalar = 1, Vector3 = 2, TangentVector = 3, IntegerLabel = 4, Uv = 5 }
    public enum PolylineKind { Guide = 1, Feature = 2 }
    public enum RetrievalDescriptor { Curv9 = 1, Hks = 3, Wks = 4, Custom = 256 }
    public enum MapStopReason { Converged = 1, Stalled = 2, IterationCap = 3, Cancelled = 4 }
    public enum MapDirection { SourceToTarget = 1, TargetToSource = 2 }
    /// <summary>mcon_map_orientation: the descriptors decide, or one orientation is forced (a "flip").</summary>
    public enum MapOrientation { Automatic = 0, Preserve = 1, Reverse = 2 }
    public enum EntryString { Name = 1, ClassLabel = 2, Author = 3, Licence = 4, Tag = 5, FieldName = 6 }
    public enum LibraryString { Name = 1, Description = 2, Descriptor = 3 }

    /// <summary>mcon_surface_point: triangle `Face` of a patch and the weights of its corners.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SurfacePoint
    {
        public uint Face; public double B0, B1, B2;
        public SurfacePoint(uint face, double b0, double b1, double b2) { Face = face; B0 = b0; B1 = b1; B2 = b2; }
    }

    /// <summary>mcon_singularity: index in quarter turns (+1 = valence 3, -1 = valence 5).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Singularity
    {
        public SurfacePoint Location; public int IndexQuarters;
        public Singularity(SurfacePoint location, int indexQuarters) { Location = location; IndexQuarters = indexQuarters; }
    }

    /// <summary>mcon_library_info (C layout).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct LibraryInfo
    {
        public uint StructSize; public UIntPtr EntryCount; public RetrievalDescriptor Descriptor; public uint DescriptorDimension;
        public uint VocabularySize; public uint Rings; public uint HistogramLength; public double SigmaBof; public ulong Seed;
        public uint FormatVersion; public uint ChecksumVerified;
    }

    /// <summary>mcon_library_entry_info (C layout).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct EntryInfo
    {
        public uint StructSize; public ulong Id; public UIntPtr VertexCount; public UIntPtr TriangleCount; public UIntPtr TagCount;
        public UIntPtr PolylineCount; public UIntPtr SingularityCount; public UIntPtr FieldCount; public SurfacePoint Center;
        public double SourceScale; public double SourceOriginX, SourceOriginY, SourceOriginZ;
        /// <summary>1 if the entry stores its source's up direction (UpX, UpY, UpZ; source coordinates).</summary>
        public uint HasUp; public double UpX, UpY, UpZ;
    }

    /// <summary>mcon_map_info (C layout).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MapInfo
    {
        public uint StructSize; public UIntPtr SourceVertexCount; public UIntPtr TargetVertexCount;
        public UIntPtr SourceVerticesInside; public UIntPtr TargetVerticesInside; public double OverlapRatio; public double MatchingScore;
        public double EnergyTotal, EnergyDescriptor, EnergyDistortion, EnergyArea, EnergyInjectivity;
        public uint Iterations; public MapStopReason StopReason; public uint Reflected; public uint Levels; public uint FlippedTriangles;
        public double AlignmentScore, AlignmentSeconds, OptimizationSeconds;
        /// <summary>Rigid scores of each orientation's best candidate (-1: not tried).</summary>
        public double AlignmentScoreUnreflected, AlignmentScoreReflected;
        /// <summary>1 if both orientations were optimized at level 0 and compared.</summary>
        public uint OrientationCompared;
        /// <summary>Their level-0 energies (-1: not compared).</summary>
        public double Level0EnergyUnreflected, Level0EnergyReflected;
        /// <summary>1 if the world-frame start decided the orientation (use_world_frame), 0 if the descriptors did.</summary>
        public uint FrameDecided;
        /// <summary>Vertices of the coarse source the first CoarseStages stages ran on (0: not used), the folds of its
        /// prolonged map that were untangled, and 1 if they could not be (those stages then ran again at full resolution).</summary>
        public uint CoarseVertices, CoarseStages, CoarseFolds, CoarseFallback;
    }

    /// <summary>mcon_cut_mesh_info (C layout): sizes of a cut mesh and what the cut changed.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct CutMeshInfo
    {
        /// <summary>sizeof(mcon_cut_mesh_info), set by mcon_cut_mesh_info_init.</summary>
        public uint StructSize;
        /// <summary>Vertices and triangles of the cut mesh.</summary>
        public UIntPtr VertexCount, TriangleCount;
        /// <summary>One chain per polyline of the set (empty if it collapsed).</summary>
        public UIntPtr GuideCount;
        /// <summary>All chains' vertices together.</summary>
        public UIntPtr GuideVertexCount;
        /// <summary>Distinct guide edges.</summary>
        public UIntPtr GuideEdgeCount;
        /// <summary>Patch triangles that were retriangulated.</summary>
        public UIntPtr CutTriangleCount;
        /// <summary>Degrees: the smallest angle of a triangle the cut made or moved.</summary>
        public double MinAngleCreated;
        /// <summary>Degrees: the smallest angle of the patch triangles it cut.</summary>
        public double MinAngleOfCutInput;
        /// <summary>Crossings moved onto a patch vertex.</summary>
        public uint SnappedToVertices;
        /// <summary>Crossings merged with another of the same edge.</summary>
        public uint MergedCrossings;
        /// <summary>Guide points dropped as adding no shape.</summary>
        public uint DroppedPoints;
        /// <summary>Steps through a snapped vertex replaced by the edge across.</summary>
        public uint Shortcuts;
        /// <summary>Snapped patch vertices moved onto their guide.</summary>
        public uint MovedVertices;
        /// <summary>Mesh.CutGuides only: guide points on hole-filling patch triangles (dropped), and the guides split there.</summary>
        public uint UnplacedPoints, SplitGuides;
        /// <summary>Chain vertices moved by fairing (fairPasses).</summary>
        public uint FairedVertices;
    }

    /// <summary>A failed Macrocon call: the C status code and the library's message.</summary>
    public class MacroconException : Exception
    {
        public Status Status { get; }
        public MacroconException(Status status, string message) : base(status + ": " + message) { Status = status; }
    }

    public sealed class CancelledException : MacroconException
    {
        public CancelledException(string message) : base(Status.Cancelled, message) { }
    }

    public sealed class InvalidMeshException : MacroconException
    {
        public InvalidMeshException(Status s, string message) : base(s, message) { }
    }

    public sealed class NotADiskException : MacroconException
    {
        public NotADiskException(string message) : base(Status.NotADisk, message) { }
    }

    public sealed class InvalidLibraryException : MacroconException
    {
        public InvalidLibraryException(string message) : base(Status.InvalidLibrary, message) { }
    }

    public sealed class NotFoundException : MacroconException
    {
        public NotFoundException(string message) : base(Status.NotFound, message) { }
    }

    /// <summary>Checks of an interleaved (strided) input before any native call: `count` rows of
    /// `rowBytes` bytes, row i at byte `offset + i * stride` of a `length`-byte buffer. The C API
    /// takes pointer + byte stride + count for per-vertex inputs (macrocon.h), so the rows are passed
    /// in place; these checks keep every byte the library reads inside the caller's buffer.</summary>
    internal static class Interleaved
    {
        /// <summary>Throws ArgumentException (naming `what`) unless the layout is valid: stride &gt; 0,
        /// offset &gt;= 0, offset + rowBytes &lt;= stride (a row fits in its record), offset and stride
        /// multiples of `alignment` (the scalar size, as in a C struct), count &gt;= 0 and the last row
        /// inside the buffer.</summary>
        internal static void Check(string what, int length, int offset, int stride, int count, int rowBytes, int alignment)
        {
            if (stride <= 0) throw new ArgumentException($"{what}: stride {stride} must be > 0 bytes");
            if (offset < 0) throw new ArgumentException($"{what}: offset {offset} must be >= 0");
            if (count < 0) throw new ArgumentException($"{what}: count {count} must be >= 0");
            if ((long)offset + rowBytes > stride)
                throw new ArgumentException($"{what}: offset {offset} + {rowBytes} bytes of a row do not fit in the stride of {stride} bytes");
            if (offset % alignment != 0 || stride % alignment != 0)
                throw new ArgumentException($"{what}: offset {offset} and stride {stride} must be multiples of {alignment} bytes");
            long needed = count == 0 ? 0 : (long)(count - 1) * stride + offset + rowBytes;
            if (needed > length)
                throw new ArgumentException($"{what}: {count} rows {stride} bytes apart from offset {offset} need {needed} bytes, the buffer holds {length}");
        }

        /// <summary>Copies `count` rows of rowBytes bytes, `stride` bytes apart from `offset` in src,
        /// into dest back to back (the layout must have passed Check).</summary>
        internal static void Pack(ReadOnlySpan<byte> src, int offset, int stride, int count, int rowBytes, Span<byte> dest)
        {
            for (int v = 0; v < count; ++v) src.Slice(offset + v * stride, rowBytes).CopyTo(dest.Slice(rowBytes * v));
        }

        /// <summary>The rows' start address, checked for the scalar alignment the C side declares.</summary>
        internal static IntPtr Start(string what, IntPtr buffer, int offset, int alignment)
        {
            IntPtr p = buffer + offset;
            if ((ulong)p.ToInt64() % (ulong)alignment != 0)
                throw new ArgumentException($"{what}: the rows start at an address that is not {alignment}-byte aligned");
            return p;
        }

        /// <summary>The size in bytes of a pinned array of a blittable element type (byte[], double[],
        /// a vendor's vertex struct array).</summary>
        internal static int ByteLength(Array array)
        {
            var element = array.GetType().GetElementType();
            long size = element.IsPrimitive ? Buffer.ByteLength(array) : (long)Marshal.SizeOf(element) * array.LongLength;
            if (size > int.MaxValue) throw new ArgumentException("interleaved records larger than 2 GiB are not supported");
            return (int)size;
        }
    }

    internal static class Native
    {
        internal const string Lib = "macrocon";
        internal const uint InvalidIndex = 0xFFFFFFFFu;

        [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
        internal delegate int ProgressCallback(IntPtr user, double fraction);

        [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
        internal delegate void LogCallback(IntPtr user, Status status, IntPtr message);

        [StructLayout(LayoutKind.Sequential)]
        internal struct ContextOptions { public uint struct_size; public uint max_threads; public IntPtr log_callback; public IntPtr log_user_data; }

        [StructLayout(LayoutKind.Sequential)]
        internal struct MeshDesc
        {
            public uint struct_size; public IntPtr positions; public uint position_type; public UIntPtr position_stride;
            public UIntPtr vertex_count; public IntPtr indices; public UIntPtr index_stride; public UIntPtr triangle_count;
            public uint index_format;  // appended: mcon_index_format (0 uint32, 1 int32, 2 int64)
            public uint flags;         // appended: mcon_mesh_flags
        }

        [StructLayout(LayoutKind.Sequential)]
        internal unsafe struct PatchOptions
        {
            public uint struct_size; public uint center_vertex; public uint center_triangle;
            public fixed double center_barycentric[3];
            public double radius; public uint flags; public double snap_fraction;
            public IntPtr progress; public IntPtr progress_user_data;
        }

        [StructLayout(LayoutKind.Sequential)]
        public unsafe struct PatchInfo
        {
            public uint struct_size; public UIntPtr vertex_count; public UIntPtr triangle_count; public UIntPtr filled_triangle_count;
            public uint boundary_loops; public int euler_characteristic; public double radius;
            public fixed double center[3];
            public uint center_patch_triangle;
            public fixed double center_barycentric[3];
            public double max_geodesic_distance; public uint param_flipped_triangles;
            public UIntPtr host_reoriented_triangles; public uint host_outward_turned_components;
            public uint host_inconsistent_components; public UIntPtr reoriented_triangles;
        }

        [StructLayout(LayoutKind.Sequential)]
        public struct PatchRepairInfo
        {
            public uint struct_size; public uint zero_area_triangles_removed; public uint triangles_split;
            public uint vertices_merged; public uint pinched_vertices_split;
        }

        [StructLayout(LayoutKind.Sequential)]
        public struct MeshOrientationInfo
        {
            public uint struct_size; public UIntPtr reoriented_triangles; public uint component_count;
            public uint closed_component_count; public uint inconsistent_component_count;
            public uint outward_turned_component_count;
        }

        [DllImport(Lib)] internal static extern Status mcon_get_version(out uint major, out uint minor, out uint patch);
        [DllImport(Lib)] internal static extern Status mcon_get_status_name(Status status, out IntPtr name);
        [DllImport(Lib)] internal static extern Status mcon_get_last_error(IntPtr context, out IntPtr message);
        [DllImport(Lib)] internal static extern Status mcon_shutdown();
        [DllImport(Lib)] internal static extern Status mcon_context_options_init_sized(ref ContextOptions options, UIntPtr structSize);
        internal static Status mcon_context_options_init(ref ContextOptions options) => mcon_context_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<ContextOptions>());
        [DllImport(Lib)] internal static extern Status mcon_context_create(ref ContextOptions options, out ContextHandle context);
        [DllImport(Lib)] internal static extern Status mcon_context_release(IntPtr context);
        [DllImport(Lib)] internal static extern Status mcon_mesh_desc_init_sized(ref MeshDesc desc, UIntPtr structSize);
        internal static Status mcon_mesh_desc_init(ref MeshDesc desc) => mcon_mesh_desc_init_sized(ref desc, (UIntPtr)Marshal.SizeOf<MeshDesc>());
        [DllImport(Lib)] internal static extern Status mcon_mesh_create(ContextHandle context, ref MeshDesc desc, out MeshHandle mesh);
        [DllImport(Lib)] internal static extern Status mcon_mesh_release(IntPtr mesh);
        [DllImport(Lib)] internal static extern Status mcon_mesh_get_counts(MeshHandle mesh, out UIntPtr vertices, out UIntPtr triangles);
        [DllImport(Lib)] internal static extern Status mcon_mesh_orientation_info_init_sized(ref MeshOrientationInfo info, UIntPtr structSize);
        internal static Status mcon_mesh_orientation_info_init(ref MeshOrientationInfo info) => mcon_mesh_orientation_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<MeshOrientationInfo>());
        [DllImport(Lib)] internal static extern Status mcon_mesh_get_orientation(MeshHandle mesh, ref MeshOrientationInfo info);
        [DllImport(Lib)] internal static extern Status mcon_mesh_get_reoriented_triangles(MeshHandle mesh, [Out] byte[] flags, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_mesh_get_triangles(MeshHandle mesh, [Out] uint[] indices, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_mesh_closest_points(MeshHandle mesh, double[] xyz, UIntPtr count,
            [Out] uint[] triangles, [Out] double[] barycentric, [Out] double[] distances);
        [DllImport(Lib)] internal static extern Status mcon_patch_options_init_sized(ref PatchOptions options, UIntPtr structSize);
        internal static Status mcon_patch_options_init(ref PatchOptions options) => mcon_patch_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<PatchOptions>());
        [DllImport(Lib)] internal static extern Status mcon_patch_extract(MeshHandle mesh, ref PatchOptions options, out PatchHandle patch);
        [DllImport(Lib)] internal static extern Status mcon_patch_release(IntPtr patch);
        [DllImport(Lib)] internal static extern Status mcon_patch_info_init_sized(ref PatchInfo info, UIntPtr structSize);
        internal static Status mcon_patch_info_init(ref PatchInfo info) => mcon_patch_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<PatchInfo>());
        [DllImport(Lib)] internal static extern Status mcon_patch_get_info(PatchHandle patch, ref PatchInfo info);
        [DllImport(Lib)] internal static extern Status mcon_patch_repair_info_init_sized(ref PatchRepairInfo info, UIntPtr structSize);
        internal static Status mcon_patch_repair_info_init(ref PatchRepairInfo info) => mcon_patch_repair_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<PatchRepairInfo>());
        [DllImport(Lib)] internal static extern Status mcon_patch_get_repairs(PatchHandle patch, ref PatchRepairInfo info);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_positions(PatchHandle patch, [Out] double[] xyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_triangles(PatchHandle patch, [Out] uint[] indices, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_uv(PatchHandle patch, [Out] double[] uv, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_host_vertices(PatchHandle patch, [Out] uint[] v0, [Out] uint[] v1, [Out] double[] t, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_host_triangles(PatchHandle patch, [Out] uint[] hostTriangles, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_compute_distance_from_point(PatchHandle patch, ref SurfacePoint point,
            [Out] double[] distances, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_compute_distance_from_vertices(PatchHandle patch, uint[] vertices,
            UIntPtr vertexCount, [Out] double[] distances, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_closest_points(PatchHandle patch, double[] xyz, UIntPtr count,
            [Out] uint[] triangles, [Out] double[] barycentric, [Out] double[] distances);
        [DllImport(Lib)] internal static extern Status mcon_descriptor_get_dimension(Descriptor descriptor, out uint dimension);
        [DllImport(Lib)] internal static extern Status mcon_patch_compute_descriptors(PatchHandle patch, Descriptor descriptor, [Out] double[] values, UIntPtr capacity);

        // ---- constraint libraries and retrieval (mcon_library_*) ----
        [StructLayout(LayoutKind.Sequential)]
        internal struct PolylineDesc { public uint kind; public uint closed; public IntPtr points; public UIntPtr point_count; }

        [StructLayout(LayoutKind.Sequential)]
        internal struct VertexField { public IntPtr name; public uint kind; public uint dimension; public IntPtr values; public IntPtr labels; public UIntPtr stride; }

        [StructLayout(LayoutKind.Sequential)]
        internal struct EntryDesc
        {
            public uint struct_size; public IntPtr patch; public ulong id; public IntPtr name; public IntPtr class_label;
            public IntPtr tags; public UIntPtr tag_count; public IntPtr author; public IntPtr licence;
            public IntPtr polylines; public UIntPtr polyline_count; public IntPtr singularities; public UIntPtr singularity_count;
            public IntPtr fields; public UIntPtr field_count; public IntPtr descriptors; public uint descriptor_dimension;
            public UIntPtr descriptor_stride; public uint has_up; public double up_x, up_y, up_z;
        }

        [StructLayout(LayoutKind.Sequential)]
        internal struct RetrievalOptions
        {
            public uint struct_size; public uint descriptor; public uint vocabulary_size; public uint rings; public double sigma_bof;
            public ulong seed; public IntPtr progress; public IntPtr progress_user_data;
        }

        [DllImport(Lib)] internal static extern Status mcon_library_entry_desc_init_sized(ref EntryDesc desc, UIntPtr structSize);

        internal static Status mcon_library_entry_desc_init(ref EntryDesc desc) => mcon_library_entry_desc_init_sized(ref desc, (UIntPtr)Marshal.SizeOf<EntryDesc>());
        [DllImport(Lib)] internal static extern Status mcon_library_create(ContextHandle context, out LibraryHandle library);
        [DllImport(Lib)] internal static extern Status mcon_library_open(ContextHandle context, byte[] path, out LibraryHandle library);
        [DllImport(Lib)] internal static extern Status mcon_library_open_memory(ContextHandle context, IntPtr data, UIntPtr size, out LibraryHandle library);
        [DllImport(Lib)] internal static extern Status mcon_library_release(IntPtr library);
        [DllImport(Lib)] internal static extern Status mcon_library_save(LibraryHandle library, byte[] path);
        [DllImport(Lib)] internal static extern Status mcon_library_save_memory(LibraryHandle library, IntPtr data, UIntPtr capacity, out UIntPtr size);
        [DllImport(Lib)] internal static extern Status mcon_library_info_init_sized(ref LibraryInfo info, UIntPtr structSize);
        internal static Status mcon_library_info_init(ref LibraryInfo info) => mcon_library_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<LibraryInfo>());
        [DllImport(Lib)] internal static extern Status mcon_library_get_info(LibraryHandle library, ref LibraryInfo info);
        [DllImport(Lib)] internal static extern Status mcon_library_get_count(LibraryHandle library, out UIntPtr count);
        [DllImport(Lib)] internal static extern Status mcon_library_get_string(LibraryHandle library, LibraryString which,
            [Out] byte[] text, UIntPtr capacity, out UIntPtr size);
        [DllImport(Lib)] internal static extern Status mcon_library_set_string(LibraryHandle library, LibraryString which, byte[] text);
        [DllImport(Lib)] internal static extern Status mcon_library_set_descriptor(LibraryHandle library, RetrievalDescriptor descriptor);
        [DllImport(Lib)] internal static extern Status mcon_library_add_entry(LibraryHandle library, ref EntryDesc desc, out ulong id);
        [DllImport(Lib)] internal static extern Status mcon_library_remove_entry(LibraryHandle library, ulong id);
        [DllImport(Lib)] internal static extern Status mcon_library_find_entry(LibraryHandle library, ulong id, out UIntPtr index);
        [DllImport(Lib)] internal static extern Status mcon_library_merge(LibraryHandle library, LibraryHandle other);
        [DllImport(Lib)] internal static extern Status mcon_retrieval_options_init_sized(ref RetrievalOptions options, UIntPtr structSize);
        internal static Status mcon_retrieval_options_init(ref RetrievalOptions options) => mcon_retrieval_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<RetrievalOptions>());
        [DllImport(Lib)] internal static extern Status mcon_library_build_retrieval(LibraryHandle library, ref RetrievalOptions options);
        [DllImport(Lib)] internal static extern Status mcon_library_query(LibraryHandle library, PatchHandle patch, UIntPtr n, [Out] ulong[] ids,
            [Out] uint[] indices, [Out] double[] distances, UIntPtr capacity, out UIntPtr count);
        [DllImport(Lib)] internal static extern Status mcon_library_query_descriptors(LibraryHandle library, PatchHandle patch, IntPtr descriptors,
            uint dimension, UIntPtr stride, UIntPtr n, [Out] ulong[] ids, [Out] uint[] indices, [Out] double[] distances, UIntPtr capacity,
            out UIntPtr count);
        [DllImport(Lib)] internal static extern Status mcon_library_entry_info_init_sized(ref EntryInfo info, UIntPtr structSize);
        internal static Status mcon_library_entry_info_init(ref EntryInfo info) => mcon_library_entry_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<EntryInfo>());
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_info(LibraryHandle library, UIntPtr index, ref EntryInfo info);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_string(LibraryHandle library, UIntPtr index, EntryString which,
            UIntPtr item, [Out] byte[] text, UIntPtr capacity, out UIntPtr size);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_positions(LibraryHandle library, UIntPtr index, [Out] double[] xyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_triangles(LibraryHandle library, UIntPtr index, [Out] uint[] indices, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_polyline(LibraryHandle library, UIntPtr index, UIntPtr polyline,
            out uint kind, out uint closed, out UIntPtr pointCount, [Out] SurfacePoint[] points, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_singularities(LibraryHandle library, UIntPtr index,
            [Out] Singularity[] singularities, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_field(LibraryHandle library, UIntPtr index, UIntPtr field,
            out uint kind, out uint dimension, [Out] double[] values, [Out] int[] labels, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_library_get_entry_retrieval(LibraryHandle library, UIntPtr index,
            [Out] double[] descriptors, UIntPtr descriptorCapacity, [Out] float[] histogram, UIntPtr histogramCapacity);

        // ---- re-embedding maps and transfer (mcon_map_*) ----
        [StructLayout(LayoutKind.Sequential)]
        internal unsafe struct PatchFrame
        {
            public uint struct_size; public uint center_triangle; public fixed double center_barycentric[3];
            public fixed double origin[3]; public double scale;
        }

        [StructLayout(LayoutKind.Sequential)]
        internal struct MapOptions
        {
            public uint struct_size; public ulong seed; public uint alignment_samples; public uint allow_reflection;
            public uint max_iterations; public IntPtr progress; public IntPtr progress_user_data;
            public uint orientation;
            public IntPtr source_guidance; public UIntPtr source_guidance_stride;
            public IntPtr target_guidance; public UIntPtr target_guidance_stride;
            public uint guidance_dimension; public double guidance_weight;
            public double refine_sigma_factor;
            public uint use_world_frame; public uint world_frame_mirror;
            public double world_frame_anchor;
            public uint use_up_hints;
            public double source_up_x, source_up_y, source_up_z;
            public double target_up_x, target_up_y, target_up_z;
            public uint coarse_stages, coarse_vertices;
        }

        [StructLayout(LayoutKind.Sequential)]
        internal struct CrossFieldOptions { public uint struct_size; public double alignment_weight; public uint align_to_boundary; public double boundary_weight; }

        [DllImport(Lib)] internal static extern Status mcon_patch_frame_init_sized(ref PatchFrame frame, UIntPtr structSize);

        internal static Status mcon_patch_frame_init(ref PatchFrame frame) => mcon_patch_frame_init_sized(ref frame, (UIntPtr)Marshal.SizeOf<PatchFrame>());
        [DllImport(Lib)] internal static extern Status mcon_patch_create_from_arrays(ContextHandle context, ref MeshDesc mesh, ref PatchFrame frame, out PatchHandle patch);
        [DllImport(Lib)] internal static extern Status mcon_map_options_init_sized(ref MapOptions options, UIntPtr structSize);
        internal static Status mcon_map_options_init(ref MapOptions options) => mcon_map_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<MapOptions>());
        [DllImport(Lib)] internal static extern Status mcon_map_compute(PatchHandle source, PatchHandle target, ref MapOptions options, out MapHandle map);
        [DllImport(Lib)] internal static extern Status mcon_map_release(IntPtr map);
        [DllImport(Lib)] internal static extern Status mcon_map_info_init_sized(ref MapInfo info, UIntPtr structSize);
        internal static Status mcon_map_info_init(ref MapInfo info) => mcon_map_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<MapInfo>());
        [DllImport(Lib)] internal static extern Status mcon_map_get_info(MapHandle map, ref MapInfo info);
        [DllImport(Lib)] internal static extern Status mcon_map_get_energy_term_count(MapHandle map, out uint count);
        [DllImport(Lib)] internal static extern Status mcon_map_get_energy_term(MapHandle map, uint index, out IntPtr name, out double value);
        [DllImport(Lib)] internal static extern Status mcon_map_get_correspondences(MapHandle map, MapDirection direction, [Out] int[] triangles,
            [Out] double[] barycentric, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_get_phi(MapHandle map, [Out] double[] xy, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_get_outside_mask(MapHandle map, [Out] byte[] mask, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_transfer_points(MapHandle map, IntPtr triangles, IntPtr barycentric, UIntPtr count,
            [Out] uint[] outTriangles, [Out] double[] outBarycentric, [Out] double[] outXyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_transfer_polylines(MapHandle map, [In] uint[] triangles, [In] double[] barycentric,
            UIntPtr pointCount, [In] uint[] sizes, [In] byte[] closed, UIntPtr polylineCount, out PolylineSetHandle polylines);
        [DllImport(Lib)] internal static extern Status mcon_polyline_set_release(IntPtr polylines);
        [DllImport(Lib)] internal static extern Status mcon_polyline_set_get_counts(PolylineSetHandle polylines, out UIntPtr polylineCount, out UIntPtr pointCount);
        [DllImport(Lib)] internal static extern Status mcon_polyline_set_get_polylines(PolylineSetHandle polylines, [Out] uint[] sizes, [Out] byte[] closed,
            [Out] uint[] inputPolyline, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_polyline_set_get_points(PolylineSetHandle polylines, [Out] uint[] triangles,
            [Out] double[] barycentric, [Out] double[] xyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_transfer_field(MapHandle map, FieldKind kind, uint dimension, IntPtr values,
            UIntPtr valueCount, [Out] double[] outValues, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_transfer_field_f32(MapHandle map, FieldKind kind, uint dimension, IntPtr values,
            UIntPtr valueCount, [Out] float[] outValues, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_map_transfer_labels(MapHandle map, uint dimension, IntPtr labels, UIntPtr labelCount,
            int outsideLabel, [Out] int[] outLabels, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cross_field_options_init_sized(ref CrossFieldOptions options, UIntPtr structSize);
        internal static Status mcon_cross_field_options_init(ref CrossFieldOptions options) => mcon_cross_field_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<CrossFieldOptions>());
        [DllImport(Lib)] internal static extern Status mcon_patch_compute_cross_field(PatchHandle patch, IntPtr guides, ref CrossFieldOptions options,
            [Out] double[] directions, [Out] double[] confidence, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_write_rosy(PatchHandle patch, IntPtr directions, UIntPtr triangleCount, byte[] path);

        // ---- guides cut into a patch (mcon_cut_mesh_*) ----
        [StructLayout(LayoutKind.Sequential)]
        internal struct GuideCutOptions
        {
            public uint struct_size; public double snap_fraction; public double simplify_fraction;
            public uint fair_passes; public double fair_max_shift;
        }

        [DllImport(Lib)] internal static extern Status mcon_guide_cut_options_init_sized(ref GuideCutOptions options, UIntPtr structSize);

        internal static Status mcon_guide_cut_options_init(ref GuideCutOptions options) => mcon_guide_cut_options_init_sized(ref options, (UIntPtr)Marshal.SizeOf<GuideCutOptions>());
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_info_init_sized(ref CutMeshInfo info, UIntPtr structSize);
        internal static Status mcon_cut_mesh_info_init(ref CutMeshInfo info) => mcon_cut_mesh_info_init_sized(ref info, (UIntPtr)Marshal.SizeOf<CutMeshInfo>());
        [DllImport(Lib)] internal static extern Status mcon_patch_cut_guides(PatchHandle patch, PolylineSetHandle guides, ref GuideCutOptions options,
            out CutMeshHandle cut);
        [DllImport(Lib)] internal static extern Status mcon_mesh_cut_guides(MeshHandle mesh, IntPtr[] guideSets, UIntPtr setCount,
            ref GuideCutOptions options, out CutMeshHandle cut);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_guide_origins(CutMeshHandle cut, [Out] uint[] sets,
            [Out] uint[] polylines, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_release(IntPtr cut);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_info(CutMeshHandle cut, ref CutMeshInfo info);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_positions(CutMeshHandle cut, [Out] double[] xyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_triangles(CutMeshHandle cut, [Out] uint[] indices, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_host_points(CutMeshHandle cut, [Out] uint[] patchTriangles,
            [Out] double[] barycentric, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_guide_edges(CutMeshHandle cut, [Out] uint[] edges, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_get_guides(CutMeshHandle cut, [Out] uint[] sizes, UIntPtr sizeCapacity,
            [Out] uint[] vertices, UIntPtr vertexCapacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_carry_field(CutMeshHandle cut, uint dimension, IntPtr patchValues,
            UIntPtr valueCount, [Out] double[] outValues, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_compute_cross_field(CutMeshHandle cut, [Out] double[] directions, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_cut_mesh_write_quadwild(CutMeshHandle cut, byte[] pathPrefix);

        /// <summary>A NUL-terminated UTF-8 copy of a string (paths and metadata); a NUL inside would cut it short.</summary>
        internal static byte[] Utf8(string s)
        {
            if (s == null) return null;
            int nul = s.IndexOf('\0');
            if (nul >= 0)
                throw new ArgumentException("the string contains a NUL character at index " + nul +
                                            ", which would cut it short on the C side: remove it");
            var bytes = System.Text.Encoding.UTF8.GetBytes(s);
            Array.Resize(ref bytes, bytes.Length + 1);
            return bytes;
        }

        internal static void Check(Status status)
        {
            if (status != Status.Ok) throw Error(status);
        }

        /// <summary>The exception of a failed call (status and the thread's last error message).</summary>
        internal static MacroconException Error(Status status)
        {
            mcon_get_last_error(IntPtr.Zero, out IntPtr msg);
            string text = msg == IntPtr.Zero ? "" : Marshal.PtrToStringAnsi(msg);
            switch (status)
            {
                case Status.Cancelled: return new CancelledException(text);
                case Status.NotADisk: return new NotADiskException(text);
                case Status.InvalidLibrary: return new InvalidLibraryException(text);
                case Status.NotFound: return new NotFoundException(text);
                case Status.NonFinite: case Status.IndexOutOfRange: case Status.RepeatedIndex: case Status.DegenerateTriangle:
                case Status.NonManifoldEdge: case Status.NonManifoldVertex: case Status.IsolatedVertex: case Status.EmptyMesh:
                case Status.NonOrientable:
                    return new InvalidMeshException(status, text);
                default: return new MacroconException(status, text);
            }
        }

        /// <summary>Check for a call that opened `path`: an IO failure on a file to read that does not
        /// exist is a System.IO.FileNotFoundException (FileName = path), on a file to write whose folder
        /// does not exist a System.IO.DirectoryNotFoundException; both name the path and carry the
        /// MacroconException (Status.IO, the library's message) as InnerException.</summary>
        internal static void CheckPath(Status status, string path, bool writing = false)
        {
            if (status == Status.Ok) return;
            MacroconException error = Error(status);  // first: reads this thread's last error
            if (status == Status.IO)
            {
                string full = System.IO.Path.GetFullPath(path);
                string missing = writing ? System.IO.Path.GetDirectoryName(full) : full;
                bool exists = writing ? System.IO.Directory.Exists(missing)
                                      : System.IO.File.Exists(missing) || System.IO.Directory.Exists(missing);
                if (!exists)
                {
                    string text = error.Message;
                    if (!text.Contains(path) && !text.Contains(missing))
                        text += writing ? " (no such folder to write in: '" + missing + "')" : " (no such file: '" + path + "')";
                    if (writing) throw new System.IO.DirectoryNotFoundException(text, error);
                    throw new System.IO.FileNotFoundException(text, path, error);
                }
            }
            throw error;
        }

        // The one native-callable progress function; `user` is a GCHandle to the managed callback.
        internal static readonly ProgressCallback Trampoline = ProgressTrampoline;
        internal static readonly IntPtr TrampolinePtr = Marshal.GetFunctionPointerForDelegate(Trampoline);

        private static int ProgressTrampoline(IntPtr user, double fraction)
        {
            var state = (ProgressState)GCHandle.FromIntPtr(user).Target;
            try { return state.Callback(fraction) ? 1 : 0; }
            catch (Exception e) { state.Error = e; return 0; }
        }

        internal sealed class ProgressState
        {
            public Func<double, bool> Callback;
            public Exception Error;
        }

        /// <summary>One call's progress callback: the static trampoline plus a GCHandle to the
        /// managed callback, freed on Dispose. Finish rethrows the callback's own exception.</summary>
        internal struct ProgressScope : IDisposable
        {
            private GCHandle gc;
            private ProgressState state;
            public IntPtr Function, UserData;

            public ProgressScope(Func<double, bool> progress)
            {
                state = new ProgressState { Callback = progress };
                gc = default;
                Function = UserData = IntPtr.Zero;
                if (progress == null) return;
                gc = GCHandle.Alloc(state);
                Function = TrampolinePtr;
                UserData = GCHandle.ToIntPtr(gc);
            }

            public void Finish(Status s)
            {
                if (s == Status.Cancelled && state.Error != null) throw state.Error;
                Check(s);
            }

            public void Dispose()
            {
                if (gc.IsAllocated) gc.Free();
            }
        }

        // ---- the log callback (mcon_context_options.log_callback) ----
        // One static, never-collected trampoline for every context. user_data is a key into
        // `logs`, not GCHandle.ToIntPtr: the native context outlives its ContextHandle while a mesh,
        // patch, map or library made in it lives (they retain it), and a message raised then
        // would resolve a freed GCHandle (undefined: a crash or another object). A key whose
        // context handle was released is simply not found, and the message is dropped.
        internal static readonly LogCallback LogTrampolineDelegate = LogTrampoline;
        internal static readonly IntPtr LogTrampolinePtr = Marshal.GetFunctionPointerForDelegate(LogTrampolineDelegate);
        private static readonly object logsLock = new object();
        private static readonly Dictionary<long, LogState> logs = new Dictionary<long, LogState>();
        private static long nextLogKey;

        internal sealed class LogState
        {
            internal const int Keep = 100;
            public Action<Status, string> Callback;
            public readonly List<Exception> Exceptions = new List<Exception>();
        }

        internal static long RegisterLog(LogState state)
        {
            lock (logsLock)
            {
                long key = ++nextLogKey;
                logs.Add(key, state);
                return key;
            }
        }

        internal static void UnregisterLog(long key)
        {
            lock (logsLock) logs.Remove(key);
        }

        // Runs on whichever thread raised the error (a TBB worker too). Nothing may unwind into C.
        private static void LogTrampoline(IntPtr user, Status status, IntPtr message)
        {
            try
            {
                LogState state;
                lock (logsLock)
                    if (!logs.TryGetValue(user.ToInt64(), out state)) return;
                // Decoded as Check decodes mcon_get_last_error: the text equals the exception's.
                string text = message == IntPtr.Zero ? "" : Marshal.PtrToStringAnsi(message);
                try { state.Callback(status, text); }
                catch (Exception e)
                {
                    lock (state.Exceptions) if (state.Exceptions.Count < LogState.Keep) state.Exceptions.Add(e);
                }
            }
            catch (Exception) { }  // e.g. out of memory while decoding: drop the message
        }

        // ---- the exit hook: release what the program left open, then mcon_shutdown ----
        // mcon_shutdown refuses while a context lives, and without it TBB's workers outlive
        // Mono's teardown (docs/design.md §5: a segfault at exit).
        private static readonly object liveLock = new object();
        private static readonly List<WeakReference<SafeHandle>> live = new List<WeakReference<SafeHandle>>();
        private static bool hookInstalled;
        internal static Status? ExitStatus;

        internal static void Track(SafeHandle h)
        {
            lock (liveLock)
            {
                if (live.Count > 64 && live.Count % 64 == 0) live.RemoveAll(w => !w.TryGetTarget(out SafeHandle x) || x.IsClosed);
                live.Add(new WeakReference<SafeHandle>(h));
                if (hookInstalled) return;
                hookInstalled = true;
                AppDomain.CurrentDomain.ProcessExit += (sender, e) => OnExit();
            }
        }

        internal static void CloseAll()
        {
            List<SafeHandle> open = new List<SafeHandle>();
            lock (liveLock)
            {
                foreach (var w in live)
                    if (w.TryGetTarget(out SafeHandle h) && !h.IsClosed) open.Add(h);
                live.Clear();
            }
            // Dependents first (the C side keeps its own references, so order is only tidiness).
            foreach (var h in open) if (!(h is ContextHandle)) h.Dispose();
            foreach (var h in open) if (h is ContextHandle) h.Dispose();
        }

        private static void OnExit()
        {
            CloseAll();
            Status s = mcon_shutdown();
            ExitStatus = s;
            if (s != Status.Ok)
            {
                mcon_get_last_error(IntPtr.Zero, out IntPtr msg);
                Console.Error.WriteLine("macrocon: mcon_shutdown at exit failed: " + (msg == IntPtr.Zero ? "" : Marshal.PtrToStringAnsi(msg)));
            }
        }
    }

    public sealed class ContextHandle : SafeHandle
    {
        // The log callback's key in Native's table (0: none); unregistered after the release.
        internal long LogKey;
        public ContextHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle()
        {
            bool ok = Native.mcon_context_release(handle) == Status.Ok;
            if (LogKey != 0) Native.UnregisterLog(LogKey);
            return ok;
        }
    }

    public sealed class MeshHandle : SafeHandle
    {
        public MeshHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_mesh_release(handle) == Status.Ok;
    }

    public sealed class PatchHandle : SafeHandle
    {
        public PatchHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_patch_release(handle) == Status.Ok;
    }

    public sealed class LibraryHandle : SafeHandle
    {
        public LibraryHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_library_release(handle) == Status.Ok;
    }

    public sealed class MapHandle : SafeHandle
    {
        public MapHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_map_release(handle) == Status.Ok;
    }

    public sealed class PolylineSetHandle : SafeHandle
    {
        public PolylineSetHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_polyline_set_release(handle) == Status.Ok;
    }

    /// <summary>Owns one reference on an mcon_cut_mesh (released with mcon_cut_mesh_release).</summary>
    public sealed class CutMeshHandle : SafeHandle
    {
        /// <summary>An empty handle, filled by mcon_patch_cut_guides.</summary>
        public CutMeshHandle() : base(IntPtr.Zero, true) { Native.Track(this); }
        /// <summary>True while no native cut mesh is held.</summary>
        public override bool IsInvalid => handle == IntPtr.Zero;
        /// <summary>Releases the native reference.</summary>
        protected override bool ReleaseHandle() => Native.mcon_cut_mesh_release(handle) == Status.Ok;
    }

    public static class Library
    {
        /// <summary>The C ABI major version this binding was written for.</summary>
        public const int AbiMajor = 0;

        public static Version Version
        {
            get
            {
                Native.Check(Native.mcon_get_version(out uint major, out uint minor, out uint patch));
                return new Version((int)major, (int)minor, (int)patch);
            }
        }

        /// <summary>Throws unless the loaded native library has this binding's ABI major version.</summary>
        public static void CheckAbi()
        {
            if (Version.Major != AbiMajor)
                throw new MacroconException(Status.Unsupported, $"native library ABI {Version.Major}, binding needs {AbiMajor}");
        }

        /// <summary>Waits for the SDK's worker threads. Call once before exit, after disposing every object.</summary>
        public static void Shutdown() => Native.Check(Native.mcon_shutdown());

        /// <summary>Disposes every Macrocon object still open in this process (they become unusable).
        /// The exit hook (AppDomain.ProcessExit) does this, then calls mcon_shutdown.</summary>
        public static void CloseAll() => Native.CloseAll();

        /// <summary>The status of the exit hook's mcon_shutdown (null until it ran; for tests).</summary>
        public static Status? ExitStatus => Native.ExitStatus;

        public static string StatusName(Status s)
        {
            Native.Check(Native.mcon_get_status_name(s, out IntPtr name));
            return Marshal.PtrToStringAnsi(name);
        }
    }

    public sealed class Context : IDisposable
    {
        internal readonly ContextHandle Handle;
        private readonly Native.LogState log;

        /// <summary>`log(status, message)`, if given, receives every error message raised in this
        /// context (calls on the context and on meshes, patches, maps and libraries made in it) with
        /// the status and text of the exception the failing call throws; it may run on any thread.
        /// An exception thrown by `log` never crosses into native code: it is kept in
        /// <see cref="LogExceptions"/> and the failing call still throws its own exception. The
        /// callback is unregistered when the context is disposed (later messages of objects that
        /// outlive it are dropped).</summary>
        public Context(uint maxThreads = 0, Action<Status, string> log = null)
        {
            var options = new Native.ContextOptions();
            Native.Check(Native.mcon_context_options_init(ref options));
            options.max_threads = maxThreads;
            long key = 0;
            if (log != null)
            {
                this.log = new Native.LogState { Callback = log };
                key = Native.RegisterLog(this.log);
                options.log_callback = Native.LogTrampolinePtr;
                options.log_user_data = new IntPtr(key);
            }
            try
            {
                Native.Check(Native.mcon_context_create(ref options, out Handle));
                Handle.LogKey = key;
            }
            catch
            {
                if (key != 0) Native.UnregisterLog(key);
                throw;
            }
        }

        /// <summary>Exceptions the log callback threw (oldest first, at most 100; empty without one).</summary>
        public IReadOnlyList<Exception> LogExceptions
        {
            get
            {
                if (log == null) return new Exception[0];
                lock (log.Exceptions) return log.Exceptions.ToArray();
            }
        }

        public void Dispose() => Handle.Dispose();
    }

    /// <summary>mcon_mesh_orientation_info: what the orientation repair of a mesh changed.</summary>
    public readonly struct MeshOrientation
    {
        public MeshOrientation(long reorientedTriangles, int components, int closedComponents, int inconsistentComponents,
                               int outwardTurnedComponents)
        {
            ReorientedTriangles = reorientedTriangles; Components = components; ClosedComponents = closedComponents;
            InconsistentComponents = inconsistentComponents; OutwardTurnedComponents = outwardTurnedComponents;
        }
        public long ReorientedTriangles { get; }
        public int Components { get; }
        public int ClosedComponents { get; }
        public int InconsistentComponents { get; }
        public int OutwardTurnedComponents { get; }
    }

    /// <summary>A triangle index array of any accepted element type as bytes plus its
    /// mcon_index_format, so every Mesh/Patch overload shares one native call.</summary>
    internal readonly ref struct Indices
    {
        public readonly ReadOnlySpan<byte> Bytes;
        public readonly uint Format;      // mcon_index_format
        public readonly int TriangleCount;

        public Indices(ReadOnlySpan<uint> t) : this(MemoryMarshal.AsBytes(t), 0, t.Length) { }
        public Indices(ReadOnlySpan<int> t) : this(MemoryMarshal.AsBytes(t), 1, t.Length) { }
        public Indices(ReadOnlySpan<long> t) : this(MemoryMarshal.AsBytes(t), 2, t.Length) { }

        private Indices(ReadOnlySpan<byte> bytes, uint format, int length)
        {
            if (length % 3 != 0) throw new ArgumentException("triangles must hold 3 indices per triangle");
            Bytes = bytes; Format = format; TriangleCount = length / 3;
        }

        public void Fill(ref Native.MeshDesc desc, IntPtr pinned)
        {
            desc.indices = pinned;
            desc.index_format = Format;
            desc.triangle_count = (UIntPtr)TriangleCount;
        }
    }

    /// <summary>mcon_mesh_flags. ValidateLocally accepts defects no operation reads (a zero-area
    /// triangle, an edge of three triangles, a pinched or isolated vertex elsewhere): Patch.Extract
    /// checks the part of the host it reads, CutGuides the whole mesh.</summary>
    [Flags]
    public enum MeshFlags : uint { None = 0, ValidateLocally = 1 }

    public sealed class Mesh : IDisposable
    {
        internal readonly MeshHandle Handle;

        /// <summary>positions: 3 per vertex; triangles: 3 indices per triangle (copied by the library).</summary>
        public Mesh(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<uint> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 2, new Indices(triangles), flags) { }

        public Mesh(Context context, ReadOnlySpan<float> positions, ReadOnlySpan<uint> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 1, new Indices(triangles), flags) { }

        /// <summary>int indices (Unity's Mesh.triangles), passed as they are (MCON_INDEX_FORMAT_INT32, no
        /// copy to uint); a negative index is a MacroconException with Status.IndexOutOfRange.</summary>
        public Mesh(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<int> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 2, new Indices(triangles), flags) { }

        public Mesh(Context context, ReadOnlySpan<float> positions, ReadOnlySpan<int> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 1, new Indices(triangles), flags) { }

        /// <summary>long indices (MCON_INDEX_FORMAT_INT64), passed as they are.</summary>
        public Mesh(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<long> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 2, new Indices(triangles), flags) { }

        public Mesh(Context context, ReadOnlySpan<float> positions, ReadOnlySpan<long> triangles, MeshFlags flags = MeshFlags.None)
            : this(context, MemoryMarshal.AsBytes(positions), 1, new Indices(triangles), flags) { }

        /// <summary>A mesh from an interleaved vertex buffer, read in place (no copy in the binding):
        /// vertex i's 3 coordinates (doubles if doublePrecision, else floats) start at byte
        /// positionOffset + i * vertexStride of vertexBytes, e.g.
        /// <c>MemoryMarshal.AsBytes(vertices.AsSpan())</c> of a vendor's vertex struct array with
        /// <c>Marshal.OffsetOf</c> of its position and <c>Marshal.SizeOf</c> as the stride.
        /// ArgumentException before the call unless vertexStride &gt; 0, the position fits inside the
        /// stride, offset and stride are multiples of the scalar size and vertexCount vertices fit in
        /// the buffer.</summary>
        public Mesh(Context context, ReadOnlySpan<byte> vertexBytes, int positionOffset, int vertexStride, int vertexCount,
                    bool doublePrecision, ReadOnlySpan<uint> triangles)
            : this(context, vertexBytes, positionOffset, vertexStride, vertexCount, doublePrecision, new Indices(triangles)) { }

        /// <summary>The interleaved constructor with int indices (Unity), passed as they are.</summary>
        public Mesh(Context context, ReadOnlySpan<byte> vertexBytes, int positionOffset, int vertexStride, int vertexCount,
                    bool doublePrecision, ReadOnlySpan<int> triangles)
            : this(context, vertexBytes, positionOffset, vertexStride, vertexCount, doublePrecision, new Indices(triangles)) { }

        private unsafe Mesh(Context context, ReadOnlySpan<byte> vertexBytes, int positionOffset, int vertexStride, int vertexCount,
                            bool doublePrecision, Indices triangles)
        {
            if (context == null) throw new ArgumentNullException(nameof(context));
            int scalar = doublePrecision ? 8 : 4;
            Interleaved.Check("vertexBytes", vertexBytes.Length, positionOffset, vertexStride, vertexCount, 3 * scalar, scalar);
            var desc = new Native.MeshDesc();
            Native.Check(Native.mcon_mesh_desc_init(ref desc));
            fixed (byte* p = &MemoryMarshal.GetReference(vertexBytes))
            fixed (byte* t = &MemoryMarshal.GetReference(triangles.Bytes))
            {
                desc.positions = vertexCount == 0 ? (IntPtr)p : Interleaved.Start("vertexBytes", (IntPtr)p, positionOffset, scalar);
                desc.position_type = doublePrecision ? 2u : 1u;
                desc.position_stride = (UIntPtr)vertexStride;
                desc.vertex_count = (UIntPtr)vertexCount;
                triangles.Fill(ref desc, (IntPtr)t);
                Native.Check(Native.mcon_mesh_create(context.Handle, ref desc, out Handle));
            }
        }

        private unsafe Mesh(Context context, ReadOnlySpan<byte> positionBytes, uint type, Indices triangles, MeshFlags flags)
        {
            int scalar = type == 1 ? 4 : 8;
            if (positionBytes.Length % (3 * scalar) != 0) throw new ArgumentException("positions must hold 3 values per vertex");
            var desc = new Native.MeshDesc();
            Native.Check(Native.mcon_mesh_desc_init(ref desc));
            fixed (byte* p = &MemoryMarshal.GetReference(positionBytes))
            fixed (byte* t = &MemoryMarshal.GetReference(triangles.Bytes))
            {
                desc.positions = (IntPtr)p;
                desc.position_type = type;
                desc.vertex_count = (UIntPtr)(positionBytes.Length / (3 * scalar));
                desc.flags = (uint)flags;
                triangles.Fill(ref desc, (IntPtr)t);
                Native.Check(Native.mcon_mesh_create(context.Handle, ref desc, out Handle));
            }
        }

        public (int Vertices, int Triangles) Counts
        {
            get
            {
                Native.Check(Native.mcon_mesh_get_counts(Handle, out UIntPtr v, out UIntPtr t));
                return ((int)v, (int)t);
            }
        }

        /// <summary>Cuts the guides of several macro constraints (each set transferred onto a patch extracted from this mesh) into the whole mesh: the result covers every face; null fractions keep the defaults.</summary>
        public CutMesh CutGuides(PolylineSet[] guideSets, double? snapFraction = null, double? simplifyFraction = null,
                                 uint? fairPasses = null)
        {
            if (guideSets == null) throw new ArgumentNullException(nameof(guideSets));
            var o = Patch.CutOptions(snapFraction, simplifyFraction, fairPasses);
            var raw = new IntPtr[guideSets.Length];
            var added = new bool[guideSets.Length];
            try
            {
                for (int i = 0; i < guideSets.Length; ++i)
                {
                    if (guideSets[i] == null) throw new ArgumentNullException($"guideSets[{i}]");
                    guideSets[i].Handle.DangerousAddRef(ref added[i]);  // alive for the call
                    raw[i] = guideSets[i].Handle.DangerousGetHandle();
                }
                Native.Check(Native.mcon_mesh_cut_guides(Handle, raw, (UIntPtr)raw.Length, ref o, out CutMeshHandle h));
                return new CutMesh(h, Counts.Vertices);
            }
            finally
            {
                for (int i = 0; i < guideSets.Length; ++i)
                    if (added[i]) guideSets[i].Handle.DangerousRelease();
            }
        }

        /// <summary>What creating the mesh changed to orient it consistently and outward.</summary>
        public MeshOrientation Orientation
        {
            get
            {
                var info = new Native.MeshOrientationInfo();
                Native.Check(Native.mcon_mesh_orientation_info_init(ref info));
                Native.Check(Native.mcon_mesh_get_orientation(Handle, ref info));
                return new MeshOrientation((long)info.reoriented_triangles, (int)info.component_count,
                                           (int)info.closed_component_count, (int)info.inconsistent_component_count,
                                           (int)info.outward_turned_component_count);
            }
        }

        /// <summary>Per input triangle: 1 if its corners 1 and 2 were swapped.</summary>
        public byte[] ReorientedTriangles()
        {
            var flags = new byte[Counts.Triangles];
            Native.Check(Native.mcon_mesh_get_reoriented_triangles(Handle, flags, (UIntPtr)flags.Length));
            return flags;
        }

        /// <summary>The oriented triangles, 3 indices each.</summary>
        public uint[] Triangles()
        {
            var indices = new uint[3 * Counts.Triangles];
            Native.Check(Native.mcon_mesh_get_triangles(Handle, indices, (UIntPtr)indices.Length));
            return indices;
        }

        /// <summary>The closest surface point to each of the points (x0 y0 z0 x1 ...).</summary>
        public ClosestPoints ClosestPoints(double[] xyz)
        {
            var c = ClosestPointsResult.Allocate(xyz, "xyz");
            Native.Check(Native.mcon_mesh_closest_points(Handle, xyz, (UIntPtr)c.Triangles.Length, c.Triangles, c.Barycentric, c.Distances));
            return c;
        }

        public void Dispose() => Handle.Dispose();
    }

    /// <summary>Closest surface points, one per query point: triangle, 3 barycentric weights (the
    /// triangle's corner order) and distance.</summary>
    public sealed class ClosestPoints
    {
        public uint[] Triangles;
        public double[] Barycentric;
        public double[] Distances;
    }

    static class ClosestPointsResult
    {
        internal static ClosestPoints Allocate(double[] xyz, string name)
        {
            if (xyz == null) throw new ArgumentNullException(name);
            if (xyz.Length % 3 != 0) throw new ArgumentException(name + " has " + xyz.Length + " values, not 3 per point", name);
            int n = xyz.Length / 3;
            return new ClosestPoints { Triangles = new uint[n], Barycentric = new double[3 * n], Distances = new double[n] };
        }
    }

    /// <summary>What Patch.Extract(..., repair: true) changed (mcon_patch_repair_info).</summary>
    public readonly struct PatchRepairs
    {
        public readonly int ZeroAreaTrianglesRemoved, TrianglesSplit, VerticesMerged, PinchedVerticesSplit;
        public PatchRepairs(int zeroArea, int split, int merged, int pinched)
        {
            ZeroAreaTrianglesRemoved = zeroArea; TrianglesSplit = split; VerticesMerged = merged; PinchedVerticesSplit = pinched;
        }
        public override string ToString() =>
            $"PatchRepairs(zero-area removed {ZeroAreaTrianglesRemoved}, split {TrianglesSplit}, merged {VerticesMerged}, pinched {PinchedVerticesSplit})";
    }

    public sealed class Patch : IDisposable
    {
        internal readonly PatchHandle Handle;
        private Native.PatchInfo info;

        private Patch(PatchHandle handle)
        {
            Handle = handle;
            info = new Native.PatchInfo();
            Native.Check(Native.mcon_patch_info_init(ref info));
            Native.Check(Native.mcon_patch_get_info(Handle, ref info));
        }

        /// <summary>Cuts the geodesic disk of `radius` around host vertex `centerVertex` (0-based).</summary>
        public static Patch Extract(Mesh mesh, uint centerVertex, double radius, bool fillHoles = true,
                                    Func<double, bool> progress = null)
            => Cut(mesh, radius, centerVertex, Native.InvalidIndex, null, fillHoles, null, progress, false);

        /// <summary>Cuts the geodesic disk of `radius` (host units) around a center on `mesh`, with the
        /// arguments of Python's Patch.extract: the center is host vertex `centerVertex` or the point
        /// of host triangle `centerTriangle` at `barycentric` (3 weights, default its centroid); give
        /// exactly one of the two (0-based), e.g.
        /// <c>Patch.Extract(mesh, radius: 0.3, centerTriangle: 12, barycentric: new[] { 0.2, 0.3, 0.5 })</c>.
        /// `fillHoles` fills enclosed pockets and inner holes; iso-line crossings closer to a vertex than
        /// `snapFraction` of the local edge length snap onto it (range [0, 0.45]; null keeps the
        /// default 0.2); `progress(fraction)` returning false cancels (CancelledException); `repair`
        /// (on a mesh made with MeshFlags.ValidateLocally) removes zero-area triangles and splits
        /// pinched vertices in the part of the host the patch reads, reported by `Repairs`.
        /// ArgumentException (before any native call) unless exactly one center is given and
        /// `barycentric`, if given, has 3 values and goes with `centerTriangle`.</summary>
        public static Patch Extract(Mesh mesh, double radius, uint? centerVertex = null, uint? centerTriangle = null,
                                    double[] barycentric = null, bool fillHoles = true, double? snapFraction = null,
                                    Func<double, bool> progress = null, bool repair = false)
        {
            if (centerVertex.HasValue == centerTriangle.HasValue)
                throw new ArgumentException("give exactly one of centerVertex and centerTriangle");
            if (barycentric != null && !centerTriangle.HasValue)
                throw new ArgumentException("barycentric places the center inside centerTriangle: give centerTriangle with it");
            if (barycentric != null && barycentric.Length != 3)
                throw new ArgumentException($"barycentric needs 3 values, got {barycentric.Length}");
            return Cut(mesh, radius, centerVertex ?? Native.InvalidIndex, centerTriangle ?? 0, barycentric, fillHoles,
                       snapFraction, progress, repair);
        }

        private static unsafe Patch Cut(Mesh mesh, double radius, uint centerVertex, uint centerTriangle, double[] barycentric,
                                        bool fillHoles, double? snapFraction, Func<double, bool> progress, bool repair)
        {
            if (mesh == null) throw new ArgumentNullException(nameof(mesh));
            var options = new Native.PatchOptions();
            Native.Check(Native.mcon_patch_options_init(ref options));
            options.center_vertex = centerVertex;
            if (centerVertex == Native.InvalidIndex)
            {
                options.center_triangle = centerTriangle;
                for (int k = 0; k < 3; ++k) options.center_barycentric[k] = barycentric == null ? 1.0 / 3 : barycentric[k];
            }
            options.radius = radius;
            options.flags = (fillHoles ? 1u : 0u) | (repair ? 2u : 0u);  // MCON_PATCH_FILL_HOLES, _REPAIR_REGION
            if (snapFraction.HasValue) options.snap_fraction = snapFraction.Value;
            using (var scope = new Native.ProgressScope(progress))
            {
                options.progress = scope.Function;
                options.progress_user_data = scope.UserData;
                Status s = Native.mcon_patch_extract(mesh.Handle, ref options, out PatchHandle handle);
                scope.Finish(s);
                return new Patch(handle);
            }
        }

        /// <summary>A patch from an already normalized disk mesh (e.g. a library entry); nothing is cut.
        /// host = origin + scale * p places it in its own host units.</summary>
        public static Patch FromArrays(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<uint> triangles,
                                       uint centerTriangle, double[] centerBarycentric = null, double[] origin = null,
                                       double scale = 1.0)
            => FromArrays(context, positions, new Indices(triangles), centerTriangle, centerBarycentric, origin, scale);

        /// <summary>FromArrays with int indices (Unity), passed as they are (MCON_INDEX_FORMAT_INT32).</summary>
        public static Patch FromArrays(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<int> triangles,
                                       uint centerTriangle, double[] centerBarycentric = null, double[] origin = null,
                                       double scale = 1.0)
            => FromArrays(context, positions, new Indices(triangles), centerTriangle, centerBarycentric, origin, scale);

        /// <summary>FromArrays with long indices (MCON_INDEX_FORMAT_INT64).</summary>
        public static Patch FromArrays(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<long> triangles,
                                       uint centerTriangle, double[] centerBarycentric = null, double[] origin = null,
                                       double scale = 1.0)
            => FromArrays(context, positions, new Indices(triangles), centerTriangle, centerBarycentric, origin, scale);

        private static unsafe Patch FromArrays(Context context, ReadOnlySpan<double> positions, Indices triangles,
                                               uint centerTriangle, double[] centerBarycentric, double[] origin, double scale)
        {
            if (positions.Length % 3 != 0) throw new ArgumentException("positions must hold 3 values per vertex");
            if (centerBarycentric != null && centerBarycentric.Length != 3) throw new ArgumentException("centerBarycentric needs 3 values");
            if (origin != null && origin.Length != 3) throw new ArgumentException("origin needs 3 values");
            var desc = new Native.MeshDesc();
            Native.Check(Native.mcon_mesh_desc_init(ref desc));
            var frame = new Native.PatchFrame();
            Native.Check(Native.mcon_patch_frame_init(ref frame));
            frame.center_triangle = centerTriangle;
            for (int k = 0; k < 3; ++k)
            {
                frame.center_barycentric[k] = centerBarycentric == null ? 1.0 / 3 : centerBarycentric[k];
                frame.origin[k] = origin == null ? 0 : origin[k];
            }
            frame.scale = scale;
            fixed (double* p = &MemoryMarshal.GetReference(positions))
            fixed (byte* t = &MemoryMarshal.GetReference(triangles.Bytes))
            {
                desc.positions = (IntPtr)p;
                desc.position_type = 2;
                desc.vertex_count = (UIntPtr)(positions.Length / 3);
                triangles.Fill(ref desc, (IntPtr)t);
                Native.Check(Native.mcon_patch_create_from_arrays(context.Handle, ref desc, ref frame, out PatchHandle handle));
                return new Patch(handle);
            }
        }

        /// <summary>A smooth per-face 4-RoSy cross field following `guides` (a PolylineSet on this patch,
        /// or null): 3 doubles per triangle, and a confidence in [0, 1] per triangle.</summary>
        public (double[] Directions, double[] Confidence) CrossField(PolylineSet guides = null, double? alignmentWeight = null,
                                                                     bool alignToBoundary = false, double? boundaryWeight = null)
        {
            var o = new Native.CrossFieldOptions();
            Native.Check(Native.mcon_cross_field_options_init(ref o));
            if (alignmentWeight.HasValue) o.alignment_weight = alignmentWeight.Value;
            o.align_to_boundary = alignToBoundary ? 1u : 0u;
            if (boundaryWeight.HasValue) o.boundary_weight = boundaryWeight.Value;
            var d = new double[3 * TriangleCount];
            var c = new double[TriangleCount];
            bool added = false;
            try
            {
                if (guides != null) guides.Handle.DangerousAddRef(ref added);
                IntPtr g = guides == null ? IntPtr.Zero : guides.Handle.DangerousGetHandle();
                Native.Check(Native.mcon_patch_compute_cross_field(Handle, g, ref o, d, c, (UIntPtr)TriangleCount));
            }
            finally
            {
                if (added) guides.Handle.DangerousRelease();
            }
            return (d, c);
        }

        /// <summary>Writes a QuadWild .rosy file (a .gz path is refused: QuadWild reads it as zeros); 3 doubles per triangle. A
        /// folder that does not exist is a System.IO.DirectoryNotFoundException naming it.</summary>
        public unsafe void WriteRosy(ReadOnlySpan<double> directions, string path)
        {
            if (directions.Length != 3 * TriangleCount) throw new ArgumentException($"directions must hold 3 * {TriangleCount} values");
            if (path == null) throw new ArgumentNullException(nameof(path));
            fixed (double* d = &MemoryMarshal.GetReference(directions))
                Native.CheckPath(Native.mcon_patch_write_rosy(Handle, (IntPtr)d, (UIntPtr)TriangleCount, Native.Utf8(path)), path,
                                 writing: true);
        }

        /// <summary>Cuts `guides` (a PolylineSet transferred onto this patch) into it: a new mesh in which every guide is a chain of edges; null options keep mcon_guide_cut_options_init's defaults (fairPasses 3, 0 = no chain fairing).</summary>
        public CutMesh CutGuides(PolylineSet guides, double? snapFraction = null, double? simplifyFraction = null,
                                 uint? fairPasses = null)
        {
            if (guides == null) throw new ArgumentNullException(nameof(guides));
            var o = CutOptions(snapFraction, simplifyFraction, fairPasses);
            Native.Check(Native.mcon_patch_cut_guides(Handle, guides.Handle, ref o, out CutMeshHandle h));
            return new CutMesh(h, VertexCount);
        }

        internal static Native.GuideCutOptions CutOptions(double? snapFraction, double? simplifyFraction, uint? fairPasses)
        {
            var o = new Native.GuideCutOptions();
            Native.Check(Native.mcon_guide_cut_options_init(ref o));
            if (snapFraction.HasValue) o.snap_fraction = snapFraction.Value;
            if (simplifyFraction.HasValue) o.simplify_fraction = simplifyFraction.Value;
            if (fairPasses.HasValue) o.fair_passes = fairPasses.Value;
            return o;
        }

        /// <summary>What `repair: true` changed in the part of the host the patch read (all 0 otherwise).</summary>
        public PatchRepairs Repairs
        {
            get
            {
                var r = new Native.PatchRepairInfo();
                Native.Check(Native.mcon_patch_repair_info_init(ref r));
                Native.Check(Native.mcon_patch_get_repairs(Handle, ref r));
                return new PatchRepairs((int)r.zero_area_triangles_removed, (int)r.triangles_split, (int)r.vertices_merged,
                                        (int)r.pinched_vertices_split);
            }
        }

        public int VertexCount => (int)info.vertex_count;
        public int TriangleCount => (int)info.triangle_count;
        public int BoundaryLoops => (int)info.boundary_loops;
        public int EulerCharacteristic => info.euler_characteristic;
        public int ParamFlippedTriangles => (int)info.param_flipped_triangles;
        /// <summary>Host triangles the orientation repair reversed, and how many of this patch's lie in one.</summary>
        public long HostReorientedTriangles => (long)info.host_reoriented_triangles;
        public long ReorientedTriangles => (long)info.reoriented_triangles;
        public int HostOutwardTurnedComponents => (int)info.host_outward_turned_components;
        public int HostInconsistentComponents => (int)info.host_inconsistent_components;
        public double MaxGeodesicDistance => info.max_geodesic_distance;
        public double Radius => info.radius;
        public unsafe double[] Center { get { fixed (double* c = info.center) return new[] { c[0], c[1], c[2] }; } }
        // The center as a point of the patch's own mesh (what FromArrays takes back).
        public uint CenterPatchTriangle => info.center_patch_triangle;
        public unsafe double[] CenterBarycentric { get { fixed (double* c = info.center_barycentric) return new[] { c[0], c[1], c[2] }; } }

        public double[] Positions()
        {
            var a = new double[3 * VertexCount];
            Native.Check(Native.mcon_patch_get_positions(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        public double[] Uv()
        {
            var a = new double[2 * VertexCount];
            Native.Check(Native.mcon_patch_get_uv(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        public uint[] Triangles()
        {
            var a = new uint[3 * TriangleCount];
            Native.Check(Native.mcon_patch_get_triangles(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        public (uint[] V0, uint[] V1, double[] T) HostVertices()
        {
            var v0 = new uint[VertexCount]; var v1 = new uint[VertexCount]; var t = new double[VertexCount];
            Native.Check(Native.mcon_patch_get_host_vertices(Handle, v0, v1, t, (UIntPtr)VertexCount));
            return (v0, v1, t);
        }

        public uint[] HostTriangles()
        {
            var a = new uint[TriangleCount];
            Native.Check(Native.mcon_patch_get_host_triangles(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        /// <summary>As Mesh.ClosestPoints on this patch, with the points and distances in host units.</summary>
        public ClosestPoints ClosestPoints(double[] xyz)
        {
            var c = ClosestPointsResult.Allocate(xyz, "xyz");
            Native.Check(Native.mcon_patch_closest_points(Handle, xyz, (UIntPtr)c.Triangles.Length, c.Triangles, c.Barycentric, c.Distances));
            return c;
        }

        /// <summary>Geodesic distance (normalized units) of every vertex from a point of the patch.</summary>
        public double[] DistanceFromPoint(SurfacePoint point)
        {
            var d = new double[VertexCount];
            Native.Check(Native.mcon_patch_compute_distance_from_point(Handle, ref point, d, (UIntPtr)d.Length));
            return d;
        }

        /// <summary>The same from the nearest of a set of patch vertices.</summary>
        public double[] DistanceFromVertices(uint[] vertices)
        {
            if (vertices == null) throw new ArgumentNullException(nameof(vertices));
            var d = new double[VertexCount];
            Native.Check(Native.mcon_patch_compute_distance_from_vertices(Handle, vertices, (UIntPtr)vertices.Length, d, (UIntPtr)d.Length));
            return d;
        }

        /// <summary>Vertex-major descriptor values (9 per vertex for Curv9, 1 for MeanCurvature).</summary>
        public double[] Descriptors(Descriptor kind)
        {
            Native.Check(Native.mcon_descriptor_get_dimension(kind, out uint dim));
            var a = new double[dim * VertexCount];
            Native.Check(Native.mcon_patch_compute_descriptors(Handle, kind, a, (UIntPtr)a.Length));
            return a;
        }

        public void Dispose() => Handle.Dispose();
    }
}
