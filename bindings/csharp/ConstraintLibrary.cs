// Constraint libraries and retrieval (mcon_library_*) for C#. The class is ConstraintLibrary
// because `Library` is the binding's static class (version, shutdown).
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;

namespace Macrocon
{
    /// <summary>A guide or feature polyline: points on a patch's triangles.</summary>
    public sealed class Polyline
    {
        public PolylineKind Kind = PolylineKind.Guide;
        public bool Closed;
        public SurfacePoint[] Points = new SurfacePoint[0];
    }

    /// <summary>A named per-vertex field: Values (real kinds) or Labels (IntegerLabel), vertex-major,
    /// Dimension channels per vertex; or, for a field that lives inside interleaved per-vertex
    /// records, Records (see <see cref="FromRecords"/>).</summary>
    public sealed class Field
    {
        public string Name;
        public FieldKind Kind = FieldKind.Scalar;
        public int Dimension = 1;
        public double[] Values;
        public int[] Labels;
        /// <summary>Instead of Values/Labels: an array of a blittable type (byte[], double[], a vendor's
        /// vertex struct array) in which vertex v's Dimension doubles (int32 for IntegerLabel) start
        /// at byte RecordOffset + v * RecordStride. AddEntry pins it and passes the stride to the
        /// library (mcon_vertex_field.stride): read in place, no copy in the binding.</summary>
        public Array Records;
        public int RecordOffset, RecordStride;

        /// <summary>A field inside interleaved records (e.g. <c>Marshal.OffsetOf(typeof(Vertex), "Weights")</c>
        /// and <c>Marshal.SizeOf(typeof(Vertex))</c>); the layout is checked by AddEntry (ArgumentException).</summary>
        public static Field FromRecords(string name, FieldKind kind, int dimension, Array records, int offset, int stride) =>
            new Field { Name = name, Kind = kind, Dimension = dimension, Records = records, RecordOffset = offset, RecordStride = stride };
    }

    /// <summary>What an entry carries besides its patch (all optional).</summary>
    public sealed class EntryDesc
    {
        public ulong Id;
        public string Name, ClassLabel, Author, Licence;
        public IReadOnlyList<string> Tags = new string[0];
        public IReadOnlyList<Polyline> Polylines = new Polyline[0];
        public Singularity[] Singularities = new Singularity[0];
        public IReadOnlyList<Field> Fields = new Field[0];
        /// <summary>Caller-supplied descriptors (a Custom library): VertexCount * DescriptorDimension values.</summary>
        public double[] Descriptors;
        public int DescriptorDimension;
        /// <summary>Instead of Descriptors: rows inside interleaved records (a blittable array, as
        /// Field.Records), DescriptorDimension doubles per vertex at byte DescriptorOffset + v *
        /// DescriptorStride; passed in place with descriptor_stride.</summary>
        public Array DescriptorRecords;
        public int DescriptorOffset, DescriptorStride;
        /// <summary>The up direction of the patch's host in its coordinates (3 numbers, not all 0),
        /// stored with the entry as the SourceUp of later maps; null: none.</summary>
        public double[] Up;
    }

    /// <summary>Retrieval settings; null members keep the library's defaults.</summary>
    public sealed class RetrievalSettings
    {
        public RetrievalDescriptor Descriptor = RetrievalDescriptor.Curv9;
        public uint? VocabularySize, Rings;
        public double? SigmaBof;
        public ulong Seed;
    }

    public sealed class QueryResult
    {
        public ulong[] Ids; public uint[] Indices; public double[] Distances;
        public int Count => Ids.Length;
    }

    /// <summary>Pins arrays and UTF-8 strings for the duration of one call (the C side copies them).</summary>
    internal sealed class Pins : IDisposable
    {
        private readonly List<GCHandle> handles = new List<GCHandle>();

        public IntPtr Pin(object array)
        {
            if (array == null) return IntPtr.Zero;
            var h = GCHandle.Alloc(array, GCHandleType.Pinned);
            handles.Add(h);
            return h.AddrOfPinnedObject();
        }

        public IntPtr Utf8(string s) => Pin(Native.Utf8(s));

        public void Dispose()
        {
            foreach (var h in handles) h.Free();
            handles.Clear();
        }
    }

    public sealed class ConstraintLibrary : IDisposable
    {
        internal readonly LibraryHandle Handle;

        private ConstraintLibrary(LibraryHandle handle) { Handle = handle; }

        /// <summary>An empty library (no vocabulary yet) whose entries are described by `descriptor`.</summary>
        public ConstraintLibrary(Context context, RetrievalDescriptor descriptor = RetrievalDescriptor.Curv9)
        {
            if (context == null) throw new ArgumentNullException(nameof(context));
            Native.Check(Native.mcon_library_create(context.Handle, out Handle));
            if (descriptor != RetrievalDescriptor.Curv9) SetDescriptor(descriptor);
        }

        /// <summary>The built-in descriptor of an empty library (one with entries changes it by BuildRetrieval).</summary>
        public void SetDescriptor(RetrievalDescriptor descriptor) =>
            Native.Check(Native.mcon_library_set_descriptor(Handle, descriptor));

        public string GetString(LibraryString which) =>
            ReadString((byte[] text, UIntPtr capacity, out UIntPtr size) =>
                Native.mcon_library_get_string(Handle, which, text, capacity, out size));

        private delegate Status StringCall(byte[] text, UIntPtr capacity, out UIntPtr size);

        // A string out of the C convention: once for the size (text null), then into a buffer of it.
        private static string ReadString(StringCall call)
        {
            Native.Check(call(null, UIntPtr.Zero, out UIntPtr size));
            var buf = new byte[(int)size];
            Native.Check(call(buf, size, out size));
            return System.Text.Encoding.UTF8.GetString(buf, 0, Math.Max(0, (int)size - 1));
        }

        /// <summary>The library's name, kept by Save and Open.</summary>
        public string Name
        {
            get => GetString(LibraryString.Name);
            set => Native.Check(Native.mcon_library_set_string(Handle, LibraryString.Name, Native.Utf8(value)));
        }

        public string Description
        {
            get => GetString(LibraryString.Description);
            set => Native.Check(Native.mcon_library_set_string(Handle, LibraryString.Description, Native.Utf8(value)));
        }

        /// <summary>The stored descriptor name: "curv9", "hks", "wks" or a custom library's own.</summary>
        public string DescriptorName => GetString(LibraryString.Descriptor);

        /// <summary>Validates and opens a file: System.IO.FileNotFoundException (FileName = path, the
        /// MacroconException with Status.IO as InnerException) if there is none, else a
        /// MacroconException (IO, InvalidLibrary, Unsupported).</summary>
        public static ConstraintLibrary Open(Context context, string path)
        {
            if (context == null) throw new ArgumentNullException(nameof(context));
            if (path == null) throw new ArgumentNullException(nameof(path));
            Native.CheckPath(Native.mcon_library_open(context.Handle, Native.Utf8(path), out LibraryHandle h), path);
            return new ConstraintLibrary(h);
        }

        /// <summary>The same from bytes (copied).</summary>
        public static unsafe ConstraintLibrary OpenMemory(Context context, ReadOnlySpan<byte> data)
        {
            if (context == null) throw new ArgumentNullException(nameof(context));
            fixed (byte* p = &MemoryMarshal.GetReference(data))
            {
                Native.Check(Native.mcon_library_open_memory(context.Handle, (IntPtr)p, (UIntPtr)data.Length, out LibraryHandle h));
                return new ConstraintLibrary(h);
            }
        }

        /// <summary>Writes atomically: on failure the previous file is untouched. A folder that does
        /// not exist is a System.IO.DirectoryNotFoundException naming it.</summary>
        public void Save(string path)
        {
            if (path == null) throw new ArgumentNullException(nameof(path));
            Native.CheckPath(Native.mcon_library_save(Handle, Native.Utf8(path)), path, writing: true);
        }

        public unsafe byte[] SaveMemory()
        {
            Native.Check(Native.mcon_library_save_memory(Handle, IntPtr.Zero, UIntPtr.Zero, out UIntPtr size));
            var bytes = new byte[(int)size];
            fixed (byte* p = bytes)
                Native.Check(Native.mcon_library_save_memory(Handle, (IntPtr)p, size, out size));
            return bytes;
        }

        public LibraryInfo Info
        {
            get
            {
                var i = new LibraryInfo();
                Native.Check(Native.mcon_library_info_init(ref i));
                Native.Check(Native.mcon_library_get_info(Handle, ref i));
                return i;
            }
        }

        public int Count
        {
            get
            {
                Native.Check(Native.mcon_library_get_count(Handle, out UIntPtr n));
                return (int)n;
            }
        }

        /// <summary>Validates and appends one entry located on `patch`; returns its id.</summary>
        public ulong AddEntry(Patch patch, EntryDesc e = null)
        {
            if (patch == null) throw new ArgumentNullException(nameof(patch));
            e = e ?? new EntryDesc();
            var desc = new Native.EntryDesc();
            Native.Check(Native.mcon_library_entry_desc_init(ref desc));
            bool added = false;
            using (var pins = new Pins())
            {
                try
                {
                    patch.Handle.DangerousAddRef(ref added);
                    desc.patch = patch.Handle.DangerousGetHandle();
                    desc.id = e.Id;
                    desc.name = pins.Utf8(e.Name);
                    desc.class_label = pins.Utf8(e.ClassLabel);
                    desc.author = pins.Utf8(e.Author);
                    desc.licence = pins.Utf8(e.Licence);
                    var tags = new IntPtr[Math.Max(1, e.Tags.Count)];
                    for (int i = 0; i < e.Tags.Count; ++i)
                        tags[i] = pins.Utf8(e.Tags[i] ?? throw new ArgumentNullException("Tags[" + i + "]"));
                    desc.tags = pins.Pin(tags);
                    desc.tag_count = (UIntPtr)e.Tags.Count;
                    var lines = new Native.PolylineDesc[Math.Max(1, e.Polylines.Count)];
                    for (int i = 0; i < e.Polylines.Count; ++i)
                    {
                        var p = e.Polylines[i] ?? throw new ArgumentNullException("Polylines[" + i + "]");
                        lines[i].kind = (uint)p.Kind;
                        lines[i].closed = p.Closed ? 1u : 0u;
                        lines[i].points = pins.Pin(p.Points);
                        lines[i].point_count = (UIntPtr)(p.Points?.Length ?? 0);
                    }
                    desc.polylines = pins.Pin(lines);
                    desc.polyline_count = (UIntPtr)e.Polylines.Count;
                    if (e.Singularities != null && e.Singularities.Length > 0)
                    {
                        desc.singularities = pins.Pin(e.Singularities);
                        desc.singularity_count = (UIntPtr)e.Singularities.Length;
                    }
                    var fields = new Native.VertexField[Math.Max(1, e.Fields.Count)];
                    for (int i = 0; i < e.Fields.Count; ++i)
                    {
                        var f = e.Fields[i] ?? throw new ArgumentNullException("Fields[" + i + "]");
                        if (f.Dimension < 1) throw new ArgumentException("Fields[" + i + "].Dimension must be >= 1");
                        bool labels = f.Kind == FieldKind.IntegerLabel;
                        if (f.Records != null)
                        {
                            if (f.Values != null || f.Labels != null)
                                throw new ArgumentException("Fields[" + i + "]: give Records or " + (labels ? "Labels" : "Values") + ", not both");
                            int scalar = labels ? 4 : 8;
                            string what = "Fields[" + i + "].Records";
                            IntPtr records = pins.Pin(f.Records);  // ArgumentException for a non-blittable element type
                            Interleaved.Check(what, Interleaved.ByteLength(f.Records), f.RecordOffset, f.RecordStride,
                                              patch.VertexCount, scalar * f.Dimension, scalar);
                            IntPtr start = Interleaved.Start(what, records, f.RecordOffset, scalar);
                            fields[i].name = pins.Utf8(f.Name);
                            fields[i].kind = (uint)f.Kind;
                            fields[i].dimension = checked((uint)f.Dimension);
                            if (labels) fields[i].labels = start; else fields[i].values = start;
                            fields[i].stride = (UIntPtr)f.RecordStride;
                            continue;
                        }
                        int length = labels ? (f.Labels?.Length ?? -1) : (f.Values?.Length ?? -1);
                        if (length < 0)
                            throw new ArgumentException("Fields[" + i + "] needs " + (labels ? "Labels" : "Values") + " for kind " + f.Kind);
                        if (length != f.Dimension * patch.VertexCount)
                            throw new ArgumentException($"Fields[{i}] holds {length} values, the patch needs {f.Dimension * patch.VertexCount}");
                        fields[i].name = pins.Utf8(f.Name);
                        fields[i].kind = (uint)f.Kind;
                        fields[i].dimension = checked((uint)f.Dimension);
                        if (labels) fields[i].labels = pins.Pin(f.Labels); else fields[i].values = pins.Pin(f.Values);
                    }
                    desc.fields = pins.Pin(fields);
                    desc.field_count = (UIntPtr)e.Fields.Count;
                    if (e.DescriptorRecords != null)
                    {
                        if (e.Descriptors != null) throw new ArgumentException("give Descriptors or DescriptorRecords, not both");
                        if (e.DescriptorDimension < 1) throw new ArgumentException("DescriptorDimension must be >= 1");
                        IntPtr records = pins.Pin(e.DescriptorRecords);
                        Interleaved.Check("DescriptorRecords", Interleaved.ByteLength(e.DescriptorRecords), e.DescriptorOffset,
                                          e.DescriptorStride, patch.VertexCount, 8 * e.DescriptorDimension, 8);
                        desc.descriptors = Interleaved.Start("DescriptorRecords", records, e.DescriptorOffset, 8);
                        desc.descriptor_dimension = checked((uint)e.DescriptorDimension);
                        desc.descriptor_stride = (UIntPtr)e.DescriptorStride;
                    }
                    else if (e.Descriptors != null)
                    {
                        if (e.DescriptorDimension < 1 || e.Descriptors.Length != e.DescriptorDimension * patch.VertexCount)
                            throw new ArgumentException("Descriptors must hold DescriptorDimension values per patch vertex");
                        desc.descriptors = pins.Pin(e.Descriptors);
                        desc.descriptor_dimension = checked((uint)e.DescriptorDimension);
                    }
                    if (e.Up != null)
                    {
                        if (e.Up.Length != 3) throw new ArgumentException("Up needs 3 components");
                        desc.has_up = 1;
                        desc.up_x = e.Up[0]; desc.up_y = e.Up[1]; desc.up_z = e.Up[2];
                    }
                    Native.Check(Native.mcon_library_add_entry(Handle, ref desc, out ulong id));
                    return id;
                }
                finally
                {
                    if (added) patch.Handle.DangerousRelease();
                }
            }
        }

        /// <summary>NotFoundException if no entry has this id; later indices shift down.</summary>
        public void Remove(ulong id) => Native.Check(Native.mcon_library_remove_entry(Handle, id));

        public int Find(ulong id)
        {
            Native.Check(Native.mcon_library_find_entry(Handle, id, out UIntPtr index));
            return (int)index;
        }

        /// <summary>Appends copies of `other`'s entries (taken ids are renumbered).</summary>
        public void Merge(ConstraintLibrary other)
        {
            if (other == null) throw new ArgumentNullException(nameof(other));
            Native.Check(Native.mcon_library_merge(Handle, other.Handle));
        }

        public void BuildRetrieval(RetrievalSettings settings = null, Func<double, bool> progress = null)
        {
            settings = settings ?? new RetrievalSettings();
            var o = new Native.RetrievalOptions();
            Native.Check(Native.mcon_retrieval_options_init(ref o));
            o.descriptor = (uint)settings.Descriptor;
            if (settings.VocabularySize.HasValue) o.vocabulary_size = settings.VocabularySize.Value;
            if (settings.Rings.HasValue) o.rings = settings.Rings.Value;
            if (settings.SigmaBof.HasValue) o.sigma_bof = settings.SigmaBof.Value;
            o.seed = settings.Seed;
            using (var scope = new Native.ProgressScope(progress))
            {
                o.progress = scope.Function;
                o.progress_user_data = scope.UserData;
                scope.Finish(Native.mcon_library_build_retrieval(Handle, ref o));
            }
        }

        private QueryResult Results(int n)
        {
            if (n < 1) throw new ArgumentOutOfRangeException(nameof(n), "n must be >= 1");
            int cap = Math.Min(n, Count);
            return new QueryResult { Ids = new ulong[cap], Indices = new uint[cap], Distances = new double[cap] };
        }

        private static QueryResult Trim(QueryResult r, UIntPtr count)
        {
            int k = (int)count;
            Array.Resize(ref r.Ids, k); Array.Resize(ref r.Indices, k); Array.Resize(ref r.Distances, k);
            return r;
        }

        /// <summary>QueryDescriptors with the descriptors inside interleaved per-vertex rows: vertex v's
        /// `dimension` doubles start at byte offset + v * stride of rowBytes; passed in place with that
        /// stride (mcon_library_query_descriptors takes one). ArgumentException for a layout that does
        /// not fit (stride &gt; 0, offset + row inside the stride, multiples of 8, VertexCount rows).</summary>
        public unsafe QueryResult QueryDescriptors(Patch patch, ReadOnlySpan<byte> rowBytes, int offset, int stride, int dimension, int n = 5)
        {
            if (patch == null) throw new ArgumentNullException(nameof(patch));
            if (dimension < 1) throw new ArgumentException($"dimension {dimension} must be >= 1");
            Interleaved.Check("rowBytes", rowBytes.Length, offset, stride, patch.VertexCount, 8 * dimension, 8);
            var r = Results(n);
            UIntPtr count;
            fixed (byte* d = &MemoryMarshal.GetReference(rowBytes))
                Native.Check(Native.mcon_library_query_descriptors(Handle, patch.Handle, Interleaved.Start("rowBytes", (IntPtr)d, offset, 8),
                                                                   checked((uint)dimension), (UIntPtr)stride, (UIntPtr)n, r.Ids, r.Indices,
                                                                   r.Distances, (UIntPtr)r.Ids.Length, out count));
            return Trim(r, count);
        }

        /// <summary>The n entries nearest to `patch`, best first (the library computes its descriptor).</summary>
        public QueryResult Query(Patch patch, int n = 5)
        {
            if (patch == null) throw new ArgumentNullException(nameof(patch));
            var r = Results(n);
            Native.Check(Native.mcon_library_query(Handle, patch.Handle, (UIntPtr)n, r.Ids, r.Indices, r.Distances,
                                                   (UIntPtr)r.Ids.Length, out UIntPtr count));
            return Trim(r, count);
        }

        /// <summary>The same with the caller's descriptors of `patch`: VertexCount * dimension values.</summary>
        public unsafe QueryResult QueryDescriptors(Patch patch, ReadOnlySpan<double> descriptors, int dimension, int n = 5)
        {
            if (patch == null) throw new ArgumentNullException(nameof(patch));
            if (dimension < 1 || descriptors.Length != dimension * patch.VertexCount)
                throw new ArgumentException("descriptors must hold `dimension` values per patch vertex");
            var r = Results(n);
            UIntPtr count;
            fixed (double* d = &MemoryMarshal.GetReference(descriptors))
                Native.Check(Native.mcon_library_query_descriptors(Handle, patch.Handle, (IntPtr)d, checked((uint)dimension), UIntPtr.Zero,
                                                                   (UIntPtr)n, r.Ids, r.Indices, r.Distances, (UIntPtr)r.Ids.Length,
                                                                   out count));
            return Trim(r, count);
        }

        // ---- entries (by index) ----

        public EntryInfo GetEntryInfo(int index)
        {
            var i = new EntryInfo();
            Native.Check(Native.mcon_library_entry_info_init(ref i));
            Native.Check(Native.mcon_library_get_entry_info(Handle, (UIntPtr)index, ref i));
            return i;
        }

        /// <summary>The entry's stored up direction (source coordinates), or null if it stores none.</summary>
        public double[] GetEntryUp(int index)
        {
            EntryInfo i = GetEntryInfo(index);
            return i.HasUp != 0 ? new[] { i.UpX, i.UpY, i.UpZ } : null;
        }

        public string GetEntryString(int index, EntryString which, int item = 0) =>
            ReadString((byte[] text, UIntPtr capacity, out UIntPtr size) =>
                Native.mcon_library_get_entry_string(Handle, (UIntPtr)index, which, (UIntPtr)item, text, capacity, out size));

        public string[] GetEntryTags(int index)
        {
            var tags = new string[(int)GetEntryInfo(index).TagCount];
            for (int i = 0; i < tags.Length; ++i) tags[i] = GetEntryString(index, EntryString.Tag, i);
            return tags;
        }

        public double[] GetEntryPositions(int index)
        {
            var a = new double[3 * (int)GetEntryInfo(index).VertexCount];
            Native.Check(Native.mcon_library_get_entry_positions(Handle, (UIntPtr)index, a, (UIntPtr)a.Length));
            return a;
        }

        public uint[] GetEntryTriangles(int index)
        {
            var a = new uint[3 * (int)GetEntryInfo(index).TriangleCount];
            Native.Check(Native.mcon_library_get_entry_triangles(Handle, (UIntPtr)index, a, (UIntPtr)a.Length));
            return a;
        }

        public Polyline[] GetEntryPolylines(int index)
        {
            var result = new Polyline[(int)GetEntryInfo(index).PolylineCount];
            for (int i = 0; i < result.Length; ++i)
            {
                Native.Check(Native.mcon_library_get_entry_polyline(Handle, (UIntPtr)index, (UIntPtr)i, out uint kind, out uint closed,
                                                                    out UIntPtr n, null, UIntPtr.Zero));
                var pts = new SurfacePoint[(int)n];
                Native.Check(Native.mcon_library_get_entry_polyline(Handle, (UIntPtr)index, (UIntPtr)i, out kind, out closed, out n,
                                                                    pts, n));
                result[i] = new Polyline { Kind = (PolylineKind)kind, Closed = closed != 0, Points = pts };
            }
            return result;
        }

        public Singularity[] GetEntrySingularities(int index)
        {
            var a = new Singularity[(int)GetEntryInfo(index).SingularityCount];
            Native.Check(Native.mcon_library_get_entry_singularities(Handle, (UIntPtr)index, a, (UIntPtr)a.Length));
            return a;
        }

        public Field GetEntryField(int index, int field)
        {
            int vertices = (int)GetEntryInfo(index).VertexCount;
            Native.Check(Native.mcon_library_get_entry_field(Handle, (UIntPtr)index, (UIntPtr)field, out uint kind, out uint dim,
                                                             null, null, UIntPtr.Zero));
            var f = new Field { Name = GetEntryString(index, EntryString.FieldName, field), Kind = (FieldKind)kind, Dimension = (int)dim };
            int n = vertices * (int)dim;
            if (f.Kind == FieldKind.IntegerLabel) f.Labels = new int[n]; else f.Values = new double[n];
            Native.Check(Native.mcon_library_get_entry_field(Handle, (UIntPtr)index, (UIntPtr)field, out kind, out dim, f.Values,
                                                             f.Labels, (UIntPtr)n));
            return f;
        }

        public Field[] GetEntryFields(int index)
        {
            var a = new Field[(int)GetEntryInfo(index).FieldCount];
            for (int i = 0; i < a.Length; ++i) a[i] = GetEntryField(index, i);
            return a;
        }

        /// <summary>The stored descriptors (VertexCount * DescriptorDimension) and histogram (HistogramLength).</summary>
        public (double[] Descriptors, float[] Histogram) GetEntryRetrieval(int index)
        {
            var info = Info;
            var d = new double[(int)GetEntryInfo(index).VertexCount * (int)info.DescriptorDimension];
            var h = new float[info.HistogramLength];
            Native.Check(Native.mcon_library_get_entry_retrieval(Handle, (UIntPtr)index, d, (UIntPtr)d.Length, h, (UIntPtr)h.Length));
            return (d, h);
        }

        public void Dispose() => Handle.Dispose();
    }
}
