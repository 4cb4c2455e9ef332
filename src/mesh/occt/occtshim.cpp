// occtshim.cpp: the OpenCASCADE shim (occtshim.h). Built with g++ into a
// shared library of its own (libzview-occt.so) that zview opens at run
// time, so that zview builds and runs where OCCT is missing, and the C++
// world (OCCT, its runtime, its exceptions) stays behind five C calls.
//
// STEP and IGES are read through XCAF (STEPCAFControl_Reader,
// IGESCAFControl_Reader), which keeps the assembly tree, the products'
// names and the colours; BREP through BRepTools::Read (one shape, no
// names or colours). The file's length unit is kept: the document's unit
// is set to the file's before the transfer, so coordinates come in the
// file's unit (OCCT would otherwise convert them to millimetres).
//
// Tessellation: BRepMesh_IncrementalMesh with a linear deflection
// relative to the bounding box's diagonal (ZV_OCCT_DEFLECTION, 0.1%, or
// what --tessellation says) and an angular one of ZV_OCCT_ANGULAR,
// serially (the sandbox counts threads; one picture needs no more).
// Each assembly leaf (a part placed by its instance's location) is one
// object; a face's own colour wins over its part's, the part's over the
// instance's parents'.

#include "occtshim.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Poly_Triangulation.hxx>
#include <Quantity_ColorRGBA.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TDF_ChildIterator.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <UnitsMethods.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XSControl_WorkSession.hxx>

namespace {

// ==== What is read ====

struct Part {
    TopoDS_Shape shape;     // located where the assembly places it
    TDF_Label    label;     // its label (for faces' colours), null for BREP
    std::string  name;
    int          colour;    // index into Collect::colours, -1 none
};

// An assembly is a DAG: a few kilobytes can place a part 2^60 times
// (each level two instances of the next). The walk stops at the most
// objects a scene holds (65535: scene.c), all it could show.
const size_t MAX_PARTS = 65535;

struct Collect {
    std::vector<Part>  parts;
    bool               too_many = false;
    std::vector<float> colours;   // 4 a colour
    Handle(XCAFDoc_ShapeTool) st;
    Handle(XCAFDoc_ColorTool) ct;
};

int add_colour(Collect &c, const Quantity_ColorRGBA &q)
{
    Standard_Real r, g, b;
    q.GetRGB().Values(r, g, b, Quantity_TOC_sRGB);
    float v[4] = { (float)r, (float)g, (float)b, q.Alpha() };
    for (size_t i = 0; i < c.colours.size(); i += 4)
        if (!memcmp(&c.colours[i], v, sizeof v))
            return (int)(i / 4);
    c.colours.insert(c.colours.end(), v, v + 4);
    return (int)(c.colours.size() / 4 - 1);
}

// The colour a label states (surface, else generic), -1 none.
int label_colour(Collect &c, const TDF_Label &l)
{
    Quantity_ColorRGBA q;
    if (c.ct.IsNull() || l.IsNull())
        return -1;
    if (c.ct->GetColor(l, XCAFDoc_ColorSurf, q) || c.ct->GetColor(l, XCAFDoc_ColorGen, q))
        return add_colour(c, q);
    return -1;
}

std::string label_name(const TDF_Label &l)
{
    Handle(TDataStd_Name) n;
    if (l.IsNull() || !l.FindAttribute(TDataStd_Name::GetID(), n))
        return std::string();
    TCollection_ExtendedString e = n->Get();
    std::string out;
    // UTF-16 to UTF-8 (names are mostly ASCII; the caller makes them safe to print)
    for (int i = 1; i <= e.Length(); i++) {
        unsigned u = (unsigned)e.Value(i);
        if (u < 0x80) {
            out += (char)u;
        } else if (u < 0x800) {
            out += (char)(0xC0 | (u >> 6));
            out += (char)(0x80 | (u & 0x3F));
        } else {
            out += (char)(0xE0 | (u >> 12));
            out += (char)(0x80 | ((u >> 6) & 0x3F));
            out += (char)(0x80 | (u & 0x3F));
        }
    }
    return out;
}

// An assembly's tree, depth first: each leaf one Part.
void visit(Collect &c, const TDF_Label &l, const TopLoc_Location &loc, int colour, const std::string &inst,
           int depth)
{
    if (depth > 64)
        return;   // a cycle or an absurd tree: what was reached is shown
    if (c.parts.size() >= MAX_PARTS) {
        c.too_many = true;
        return;
    }
    TDF_Label ref = l;
    TopLoc_Location here = loc;
    if (c.st->IsReference(l)) {
        c.st->GetReferredShape(l, ref);
        here = loc * c.st->GetLocation(l);
    }
    int own = label_colour(c, l);
    if (own < 0 && ref != l)
        own = label_colour(c, ref);
    if (own >= 0)
        colour = own;
    std::string name = label_name(ref);
    if (name.empty())
        name = label_name(l);
    if (name.empty())
        name = inst;
    if (c.st->IsAssembly(ref)) {
        TDF_LabelSequence comps;
        c.st->GetComponents(ref, comps);
        for (int i = 1; i <= comps.Length(); i++)
            visit(c, comps.Value(i), here, colour, name, depth + 1);
        return;
    }
    TopoDS_Shape s = c.st->GetShape(ref);
    if (s.IsNull())
        return;
    Part p;
    p.shape = here.IsIdentity() ? s : s.Moved(here);
    p.label = ref;
    p.name = name;
    p.colour = colour;
    c.parts.push_back(p);
}

// ==== Units ====

struct UnitName {
    const char *occt;   // as FileUnits names it, or a prefix of it
    const char *ours;
    double      mm;
};

const UnitName step_units[] = {
    { "MILLIMETRE", "mm", 1 }, { "MILLIMETER", "mm", 1 }, { "CENTIMETRE", "cm", 10 }, { "CENTIMETER", "cm", 10 },
    { "METRE", "m", 1000 },    { "METER", "m", 1000 },    { "INCH", "in", 25.4 },     { "FOOT", "ft", 304.8 },
    { "MICROMETRE", "um", 0.001 }, { "KILOMETRE", "km", 1e6 }, { "MIL", "mil", 0.0254 },
};

// IGES's unit flag (the global section's 14th field) is UnitsMethods_LengthUnit.
const UnitName *iges_unit(int flag)
{
    static const UnitName tab[] = {
        { "", "in", 25.4 }, { "", "mm", 1 }, { "", "", 0 }, { "", "ft", 304.8 }, { "", "mi", 1609344 },
        { "", "m", 1000 }, { "", "km", 1e6 }, { "", "mil", 0.0254 }, { "", "um", 0.001 }, { "", "cm", 10 },
        { "", "uin", 0.0000254 },
    };
    return flag >= 1 && flag <= 11 && tab[flag - 1].mm > 0 ? &tab[flag - 1] : NULL;
}

const UnitName *step_unit(STEPControl_Reader &r)
{
    TColStd_SequenceOfAsciiString len, ang, solid;
    r.FileUnits(len, ang, solid);
    if (len.IsEmpty())
        return NULL;
    TCollection_AsciiString n = len.First();
    n.UpperCase();
    for (const UnitName &u : step_units)
        if (n.IsEqual(u.occt))
            return &u;
    return NULL;
}

// ==== Tessellation and the triangles ====

struct Out {
    std::vector<float>    pos;
    std::vector<uint32_t> tri, tri_obj;
    std::vector<int32_t>  tri_colour;
    uint32_t              faces = 0, bare = 0;
};

void emit_face(Out &o, const TopoDS_Face &f, uint32_t obj, int colour)
{
    o.faces++;
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) &t = BRep_Tool::Triangulation(f, loc);
    if (t.IsNull() || t->NbTriangles() == 0) {
        o.bare++;
        return;
    }
    gp_Trsf tr = loc.Transformation();
    bool flip = (f.Orientation() == TopAbs_REVERSED) != tr.IsNegative();
    uint32_t base = (uint32_t)(o.pos.size() / 3);
    for (int i = 1; i <= t->NbNodes(); i++) {
        gp_Pnt p = t->Node(i).Transformed(tr);
        o.pos.push_back((float)p.X());
        o.pos.push_back((float)p.Y());
        o.pos.push_back((float)p.Z());
    }
    for (int i = 1; i <= t->NbTriangles(); i++) {
        int a, b, c;
        t->Triangle(i).Get(a, b, c);
        if (flip)
            std::swap(b, c);
        o.tri.push_back(base + (uint32_t)a - 1);
        o.tri.push_back(base + (uint32_t)b - 1);
        o.tri.push_back(base + (uint32_t)c - 1);
        o.tri_obj.push_back(obj);
        o.tri_colour.push_back(colour);
    }
}

template <class T> T *copy_out(const std::vector<T> &v)
{
    T *p = (T *)malloc(v.empty() ? 1 : v.size() * sizeof(T));
    if (!p)
        throw std::bad_alloc();
    if (!v.empty())
        memcpy(p, v.data(), v.size() * sizeof(T));
    return p;
}

int read_xcaf(const char *path, int kind, Collect &c, ZvOcctMesh *out, char *err, size_t errlen)
{
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    const UnitName *unit = NULL;
    if (kind == ZV_OCCT_STEP) {
        STEPCAFControl_Reader r;
        r.SetColorMode(true);
        r.SetNameMode(true);
        r.SetLayerMode(false);
        r.SetPropsMode(false);
        r.SetGDTMode(false);
        r.SetMatMode(false);
        r.SetViewMode(false);
        if (r.ReadFile(path) != IFSelect_RetDone) {
            snprintf(err, errlen, "not a STEP file OCCT can read");
            return -1;
        }
        unit = step_unit(r.ChangeReader());
        if (unit)
            XCAFDoc_DocumentTool::SetLengthUnit(doc, unit->mm, UnitsMethods_LengthUnit_Millimeter);
        if (!r.Transfer(doc)) {
            snprintf(err, errlen, "OCCT read no shapes from the STEP file");
            return -1;
        }
    } else {
        IGESCAFControl_Reader r;
        r.SetColorMode(true);
        r.SetNameMode(true);
        r.SetLayerMode(false);
        if (r.ReadFile(path) != IFSelect_RetDone) {
            snprintf(err, errlen, "not an IGES file OCCT can read");
            return -1;
        }
        Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(r.Model());
        if (!model.IsNull())
            unit = iges_unit(model->GlobalSection().UnitFlag());
        if (unit) {
            XCAFDoc_DocumentTool::SetLengthUnit(doc, unit->mm, UnitsMethods_LengthUnit_Millimeter);
            UnitsMethods::SetCasCadeLengthUnit(unit->mm, UnitsMethods_LengthUnit_Millimeter);
        }
        if (!r.Transfer(doc)) {
            snprintf(err, errlen, "OCCT read no shapes from the IGES file");
            return -1;
        }
    }
    if (unit)
        snprintf(out->unit, sizeof out->unit, "%s", unit->ours);
    c.st = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    c.ct = XCAFDoc_DocumentTool::ColorTool(doc->Main());
    TDF_LabelSequence roots;
    c.st->GetFreeShapes(roots);
    for (int i = 1; i <= roots.Length(); i++)
        visit(c, roots.Value(i), TopLoc_Location(), -1, std::string(), 0);
    return 0;
}

int read_any(const char *path, int kind, double rel, ZvOcctMesh *out, char *err, size_t errlen)
{
    Collect c;
    if (kind == ZV_OCCT_BREP) {
        TopoDS_Shape s;
        BRep_Builder b;
        if (!BRepTools::Read(s, path, b) || s.IsNull()) {
            snprintf(err, errlen, "not a BREP file OCCT can read");
            return -1;
        }
        Part p;
        p.shape = s;
        p.colour = -1;
        c.parts.push_back(p);
    } else if (read_xcaf(path, kind, c, out, err, errlen)) {
        return -1;
    }
    if (c.too_many) {
        snprintf(err, errlen, "an assembly that places more than %zu parts", MAX_PARTS);
        return -1;
    }
    if (c.parts.empty()) {
        snprintf(err, errlen, "no shapes in the file");
        return -1;
    }
    TopoDS_Compound all;
    BRep_Builder b;
    b.MakeCompound(all);
    for (const Part &p : c.parts)
        b.Add(all, p.shape);
    Bnd_Box box;
    BRepBndLib::Add(all, box);
    if (box.IsVoid()) {
        snprintf(err, errlen, "no geometry in the file");
        return -1;
    }
    double diag = std::sqrt(box.SquareExtent());
    if (!(diag > 0) || !std::isfinite(diag)) {
        snprintf(err, errlen, "a model of no size");
        return -1;
    }
    double defl = (rel > 0 ? rel : ZV_OCCT_DEFLECTION) * diag;
    BRepMesh_IncrementalMesh mesh(all, defl, Standard_False, ZV_OCCT_ANGULAR, Standard_False);
    Out o;
    std::vector<std::string> names;
    for (const Part &p : c.parts) {
        uint32_t obj = (uint32_t)names.size();
        names.push_back(p.name);
        for (TopExp_Explorer e(p.shape, TopAbs_FACE); e.More(); e.Next()) {
            const TopoDS_Face &f = TopoDS::Face(e.Current());
            int colour = p.colour;
            TDF_Label sub;
            if (!p.label.IsNull() && !c.ct.IsNull() && c.st->FindSubShape(p.label, f.Located(TopLoc_Location()), sub)) {
                int fc = label_colour(c, sub);
                if (fc >= 0)
                    colour = fc;
            }
            emit_face(o, f, obj, colour);
        }
    }
    if (o.tri.empty()) {
        snprintf(err, errlen, "no faces OCCT could tessellate (%u faces)", o.faces);
        return -1;
    }
    if (o.pos.size() / 3 >= UINT32_MAX || o.tri.size() / 3 >= UINT32_MAX) {
        snprintf(err, errlen, "too many triangles");
        return -1;
    }
    out->nverts = (uint32_t)(o.pos.size() / 3);
    out->ntris = (uint32_t)(o.tri.size() / 3);
    out->pos = copy_out(o.pos);
    out->tri = copy_out(o.tri);
    out->tri_obj = copy_out(o.tri_obj);
    out->tri_colour = copy_out(o.tri_colour);
    out->nobjs = (uint32_t)names.size();
    out->obj_name = (char **)calloc(names.size(), sizeof(char *));
    if (!out->obj_name)
        throw std::bad_alloc();
    for (size_t i = 0; i < names.size(); i++)
        if (!(out->obj_name[i] = strdup(names[i].c_str())))
            throw std::bad_alloc();
    out->ncolours = (uint32_t)(c.colours.size() / 4);
    out->colour = copy_out(c.colours);
    out->deflection = defl;
    out->diagonal = diag;
    out->faces = o.faces;
    out->bare_faces = o.bare;
    return 0;
}

} // namespace

extern "C" {

int zv_occt_abi(void) { return ZV_OCCT_ABI; }

const char *zv_occt_version(void) { return "OCCT " OCC_VERSION_COMPLETE; }

int zv_occt_init(void)
{
    try {
        // OCCT's messages go to standard output by default: zview's
        // reports are there. Nothing of OCCT's is printed.
        const Handle(Message_Messenger) &msg = Message::DefaultMessenger();
        msg->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
        STEPControl_Controller::Init();
        IGESControl_Controller::Init();
        XCAFApp_Application::GetApplication();
        Interface_Static::SetIVal("read.step.product.mode", 1);
        return 0;
    } catch (...) {
        return -1;
    }
}

int zv_occt_read(const char *path, int kind, double rel_deflection, ZvOcctMesh *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    int r = -1;
    try {
        r = read_any(path, kind, rel_deflection, out, err, errlen);
    } catch (const std::bad_alloc &) {
        snprintf(err, errlen, "out of memory reading it (OCCT)");
        r = -1;
    } catch (const Standard_Failure &f) {
        const char *w = f.GetMessageString();
        snprintf(err, errlen, "OCCT could not read it (%.200s: %.200s)", f.DynamicType()->Name(),
                 w && *w ? w : "no message");
        r = -1;
    } catch (...) {
        snprintf(err, errlen, "OCCT could not read it (an exception)");
        r = -1;
    }
    if (r)
        zv_occt_free(out);
    return r;
}

void zv_occt_free(ZvOcctMesh *m)
{
    if (!m)
        return;
    free(m->pos);
    free(m->tri);
    free(m->tri_obj);
    free(m->tri_colour);
    if (m->obj_name)
        for (uint32_t i = 0; i < m->nobjs; i++)
            free(m->obj_name[i]);
    free(m->obj_name);
    free(m->colour);
    memset(m, 0, sizeof *m);
}

} // extern "C"
