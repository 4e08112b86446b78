// C# binding over the Macrocon C ABI: P/Invoke, one SafeHandle per handle type, IDisposable
// wrappers, exceptions from status codes, arrays and spans in, progress through a static
// trampoline (the delegate never moves; the user's callback travels as a GCHandle).
using System;
using System.Runtime.InteropServices;

namespace Macrocon
{
    public enum Status
    {
        Ok = 0, Unknown = 1, InvalidArgument = 2, NullPointer = 3, StructSize = 4, OutOfMemory = 5,
        BufferTooSmall = 6, Cancelled = 7, IO = 8, NonFinite = 10, IndexOutOfRange = 11, RepeatedIndex = 12,
        DegenerateTriangle = 13, NonManifoldEdge = 14, NonManifoldVertex = 15, IsolatedVertex = 16,
        EmptyMesh = 17, NotADisk = 20, Numerical = 21, InvalidLibrary = 30, Unsupported = 31, NotFound = 32,
    }

    public enum Descriptor { Curv9 = 1, MeanCurvature = 2 }

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

    internal static class Native
    {
        internal const string Lib = "macrocon";
        internal const uint InvalidIndex = 0xFFFFFFFFu;

        [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
        internal delegate int ProgressCallback(IntPtr user, double fraction);

        [StructLayout(LayoutKind.Sequential)]
        internal struct ContextOptions { public uint struct_size; public uint max_threads; public IntPtr log_callback; public IntPtr log_user_data; }

        [StructLayout(LayoutKind.Sequential)]
        internal struct MeshDesc
        {
            public uint struct_size; public IntPtr positions; public uint position_type; public UIntPtr position_stride;
            public UIntPtr vertex_count; public IntPtr indices; public UIntPtr index_stride; public UIntPtr triangle_count;
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
        }

        [DllImport(Lib)] internal static extern Status mcon_get_version(out uint major, out uint minor, out uint patch);
        [DllImport(Lib)] internal static extern Status mcon_get_status_name(Status status, out IntPtr name);
        [DllImport(Lib)] internal static extern Status mcon_get_last_error(IntPtr context, out IntPtr message);
        [DllImport(Lib)] internal static extern Status mcon_shutdown();
        [DllImport(Lib)] internal static extern Status mcon_context_options_init(ref ContextOptions options);
        [DllImport(Lib)] internal static extern Status mcon_context_create(ref ContextOptions options, out ContextHandle context);
        [DllImport(Lib)] internal static extern Status mcon_context_release(IntPtr context);
        [DllImport(Lib)] internal static extern Status mcon_mesh_desc_init(ref MeshDesc desc);
        [DllImport(Lib)] internal static extern Status mcon_mesh_create(ContextHandle context, ref MeshDesc desc, out MeshHandle mesh);
        [DllImport(Lib)] internal static extern Status mcon_mesh_release(IntPtr mesh);
        [DllImport(Lib)] internal static extern Status mcon_mesh_get_counts(MeshHandle mesh, out UIntPtr vertices, out UIntPtr triangles);
        [DllImport(Lib)] internal static extern Status mcon_patch_options_init(ref PatchOptions options);
        [DllImport(Lib)] internal static extern Status mcon_patch_extract(MeshHandle mesh, ref PatchOptions options, out PatchHandle patch);
        [DllImport(Lib)] internal static extern Status mcon_patch_release(IntPtr patch);
        [DllImport(Lib)] internal static extern Status mcon_patch_info_init(ref PatchInfo info);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_info(PatchHandle patch, ref PatchInfo info);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_positions(PatchHandle patch, [Out] double[] xyz, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_triangles(PatchHandle patch, [Out] uint[] indices, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_uv(PatchHandle patch, [Out] double[] uv, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_host_vertices(PatchHandle patch, [Out] uint[] v0, [Out] uint[] v1, [Out] double[] t, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_patch_get_host_triangles(PatchHandle patch, [Out] uint[] hostTriangles, UIntPtr capacity);
        [DllImport(Lib)] internal static extern Status mcon_descriptor_get_dimension(Descriptor descriptor, out uint dimension);
        [DllImport(Lib)] internal static extern Status mcon_patch_compute_descriptors(PatchHandle patch, Descriptor descriptor, [Out] double[] values, UIntPtr capacity);

        internal static void Check(Status status)
        {
            if (status == Status.Ok) return;
            mcon_get_last_error(IntPtr.Zero, out IntPtr msg);
            string text = msg == IntPtr.Zero ? "" : Marshal.PtrToStringAnsi(msg);
            switch (status)
            {
                case Status.Cancelled: throw new CancelledException(text);
                case Status.NotADisk: throw new NotADiskException(text);
                case Status.NonFinite: case Status.IndexOutOfRange: case Status.RepeatedIndex: case Status.DegenerateTriangle:
                case Status.NonManifoldEdge: case Status.NonManifoldVertex: case Status.IsolatedVertex: case Status.EmptyMesh:
                    throw new InvalidMeshException(status, text);
                default: throw new MacroconException(status, text);
            }
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
    }

    public sealed class ContextHandle : SafeHandle
    {
        public ContextHandle() : base(IntPtr.Zero, true) { }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_context_release(handle) == Status.Ok;
    }

    public sealed class MeshHandle : SafeHandle
    {
        public MeshHandle() : base(IntPtr.Zero, true) { }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_mesh_release(handle) == Status.Ok;
    }

    public sealed class PatchHandle : SafeHandle
    {
        public PatchHandle() : base(IntPtr.Zero, true) { }
        public override bool IsInvalid => handle == IntPtr.Zero;
        protected override bool ReleaseHandle() => Native.mcon_patch_release(handle) == Status.Ok;
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

        public static string StatusName(Status s)
        {
            Native.Check(Native.mcon_get_status_name(s, out IntPtr name));
            return Marshal.PtrToStringAnsi(name);
        }
    }

    public sealed class Context : IDisposable
    {
        internal readonly ContextHandle Handle;

        public Context(uint maxThreads = 0)
        {
            var options = new Native.ContextOptions();
            Native.Check(Native.mcon_context_options_init(ref options));
            options.max_threads = maxThreads;
            Native.Check(Native.mcon_context_create(ref options, out Handle));
        }

        public void Dispose() => Handle.Dispose();
    }

    public sealed class Mesh : IDisposable
    {
        internal readonly MeshHandle Handle;

        /// <summary>positions: 3 per vertex; triangles: 3 indices per triangle (copied by the library).</summary>
        public Mesh(Context context, ReadOnlySpan<double> positions, ReadOnlySpan<uint> triangles)
            : this(context, MemoryMarshal.AsBytes(positions), 2, triangles) { }

        public Mesh(Context context, ReadOnlySpan<float> positions, ReadOnlySpan<uint> triangles)
            : this(context, MemoryMarshal.AsBytes(positions), 1, triangles) { }

        private unsafe Mesh(Context context, ReadOnlySpan<byte> positionBytes, uint type, ReadOnlySpan<uint> triangles)
        {
            int scalar = type == 1 ? 4 : 8;
            if (positionBytes.Length % (3 * scalar) != 0) throw new ArgumentException("positions must hold 3 values per vertex");
            if (triangles.Length % 3 != 0) throw new ArgumentException("triangles must hold 3 indices per triangle");
            var desc = new Native.MeshDesc();
            Native.Check(Native.mcon_mesh_desc_init(ref desc));
            fixed (byte* p = &MemoryMarshal.GetReference(positionBytes))
            fixed (uint* t = &MemoryMarshal.GetReference(triangles))
            {
                desc.positions = (IntPtr)p;
                desc.position_type = type;
                desc.vertex_count = (UIntPtr)(positionBytes.Length / (3 * scalar));
                desc.indices = (IntPtr)t;
                desc.triangle_count = (UIntPtr)(triangles.Length / 3);
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

        public void Dispose() => Handle.Dispose();
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

        /// <summary>Cuts the geodesic disk of `radius` around host vertex `centerVertex`.</summary>
        public static unsafe Patch Extract(Mesh mesh, uint centerVertex, double radius, bool fillHoles = true,
                                           Func<double, bool> progress = null)
        {
            var options = new Native.PatchOptions();
            Native.Check(Native.mcon_patch_options_init(ref options));
            options.center_vertex = centerVertex;
            options.radius = radius;
            options.flags = fillHoles ? 1u : 0u;
            var state = new Native.ProgressState { Callback = progress };
            GCHandle gc = default;
            if (progress != null)
            {
                gc = GCHandle.Alloc(state);
                options.progress = Native.TrampolinePtr;
                options.progress_user_data = GCHandle.ToIntPtr(gc);
            }
            try
            {
                Status s = Native.mcon_patch_extract(mesh.Handle, ref options, out PatchHandle handle);
                if (s == Status.Cancelled && state.Error != null) throw state.Error;
                Native.Check(s);
                return new Patch(handle);
            }
            finally
            {
                if (gc.IsAllocated) gc.Free();
            }
        }

        public int VertexCount => (int)info.vertex_count;
        public int TriangleCount => (int)info.triangle_count;
        public int BoundaryLoops => (int)info.boundary_loops;
        public int EulerCharacteristic => info.euler_characteristic;
        public int ParamFlippedTriangles => (int)info.param_flipped_triangles;
        public double MaxGeodesicDistance => info.max_geodesic_distance;
        public double Radius => info.radius;
        public unsafe double[] Center { get { fixed (double* c = info.center) return new[] { c[0], c[1], c[2] }; } }

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
