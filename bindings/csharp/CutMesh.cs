// Guides cut into a patch (mcon_patch_cut_guides, mcon_cut_mesh_*) for C#: the cut mesh, its guide
// chains and edges, fields carried onto it, its guide-following cross field and QuadWild's inputs.
using System;
using System.Runtime.InteropServices;

namespace Macrocon
{
    /// <summary>Where a cut-mesh guide chain comes from: its guide set and the polyline of that set.</summary>
    public struct GuideOrigin
    {
        public uint Set, Polyline;
    }

    /// <summary>A patch's surface (Patch.CutGuides) or a whole mesh (Mesh.CutGuides) re-meshed so that every guide is a chain of edges; keeps its input alive.</summary>
    public sealed class CutMesh : IDisposable
    {
        internal readonly CutMeshHandle Handle;
        private readonly int patchVertices;

        internal CutMesh(CutMeshHandle handle, int patchVertices)
        {
            Handle = handle;
            this.patchVertices = patchVertices;
        }

        /// <summary>Sizes of the cut mesh and what the cut changed (mcon_cut_mesh_get_info).</summary>
        public CutMeshInfo Info
        {
            get
            {
                var i = new CutMeshInfo();
                Native.Check(Native.mcon_cut_mesh_info_init(ref i));
                Native.Check(Native.mcon_cut_mesh_get_info(Handle, ref i));
                return i;
            }
        }

        /// <summary>Vertex positions in the patch's host units, 3 doubles per vertex.</summary>
        public double[] Positions()
        {
            var a = new double[3 * (int)Info.VertexCount];
            Native.Check(Native.mcon_cut_mesh_get_positions(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        /// <summary>Triangles, 3 vertex indices each, in the patch's winding.</summary>
        public uint[] Triangles()
        {
            var a = new uint[3 * (int)Info.TriangleCount];
            Native.Check(Native.mcon_cut_mesh_get_triangles(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        /// <summary>Per vertex the patch triangle its host point lies in.</summary>
        public uint[] HostTriangles()
        {
            int n = (int)Info.VertexCount;
            var t = new uint[n];
            Native.Check(Native.mcon_cut_mesh_get_host_points(Handle, t, null, (UIntPtr)n));
            return t;
        }

        /// <summary>Per vertex the 3 barycentric weights of its host point in its HostTriangles() triangle.</summary>
        public double[] HostBarycentric()
        {
            int n = (int)Info.VertexCount;
            var b = new double[3 * n];
            Native.Check(Native.mcon_cut_mesh_get_host_points(Handle, null, b, (UIntPtr)n));
            return b;
        }

        /// <summary>The distinct guide edges as vertex pairs, 2 indices each.</summary>
        public uint[] GuideEdges()
        {
            var a = new uint[2 * (int)Info.GuideEdgeCount];
            Native.Check(Native.mcon_cut_mesh_get_guide_edges(Handle, a, (UIntPtr)a.Length));
            return a;
        }

        /// <summary>One vertex chain per guide (a closed guide repeats its first vertex at its end; a collapsed one is empty).</summary>
        public uint[][] Guides()
        {
            var i = Info;
            var sizes = new uint[(int)i.GuideCount];
            var all = new uint[(int)i.GuideVertexCount];
            Native.Check(Native.mcon_cut_mesh_get_guides(Handle, sizes, (UIntPtr)sizes.Length, all, (UIntPtr)all.Length));
            var chains = new uint[sizes.Length][];
            int at = 0;
            for (int g = 0; g < sizes.Length; ++g)
            {
                chains[g] = new uint[sizes[g]];
                Array.Copy(all, at, chains[g], 0, (int)sizes[g]);
                at += (int)sizes[g];
            }
            return chains;
        }

        /// <summary>Per guide chain its guide set (0 for Patch.CutGuides) and the polyline of that set it comes from.</summary>
        public GuideOrigin[] GuideOrigins()
        {
            int n = (int)Info.GuideCount;
            var sets = new uint[n];
            var lines = new uint[n];
            Native.Check(Native.mcon_cut_mesh_get_guide_origins(Handle, sets, lines, (UIntPtr)n));
            var o = new GuideOrigin[n];
            for (int g = 0; g < n; ++g) o[g] = new GuideOrigin { Set = sets[g], Polyline = lines[g] };
            return o;
        }

        /// <summary>A per-vertex field of the patch (of the mesh for Mesh.CutGuides; dimension values per vertex) interpolated at the cut mesh's vertices.</summary>
        public unsafe double[] CarryField(ReadOnlySpan<double> patchValues, int dimension)
        {
            if (dimension < 1 || patchValues.Length != (long)dimension * patchVertices)
                throw new ArgumentException($"patchValues must hold {dimension} per input vertex ({patchVertices})");
            var o = new double[dimension * (int)Info.VertexCount];
            fixed (double* v = &MemoryMarshal.GetReference(patchValues))
                Native.Check(Native.mcon_cut_mesh_carry_field(Handle, checked((uint)dimension), (IntPtr)v, (UIntPtr)patchValues.Length, o,
                                                              (UIntPtr)o.Length));
            return o;
        }

        /// <summary>A per-face 4-RoSy cross field exactly along the guide edges on their faces and smooth elsewhere, 3 doubles per triangle.</summary>
        public double[] CrossField()
        {
            int n = (int)Info.TriangleCount;
            var d = new double[3 * n];
            Native.Check(Native.mcon_cut_mesh_compute_cross_field(Handle, d, (UIntPtr)n));
            return d;
        }

        /// <summary>Writes QuadWild's `pathPrefix`.obj/.rosy/.sharp and a .quadwild.json manifest; a folder that does not exist is a System.IO.DirectoryNotFoundException naming it.</summary>
        public void WriteQuadWild(string pathPrefix)
        {
            if (pathPrefix == null) throw new ArgumentNullException(nameof(pathPrefix));
            Native.CheckPath(Native.mcon_cut_mesh_write_quadwild(Handle, Native.Utf8(pathPrefix)), pathPrefix, writing: true);
        }

        /// <summary>Releases this wrapper's reference on the native cut mesh.</summary>
        public void Dispose() => Handle.Dispose();
    }
}
