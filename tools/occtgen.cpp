// occtgen: the STEP, IGES and BREP files of the tests (tests/e2e/test_step.sh),
// written through OpenCASCADE itself, with known shapes:
//   box.step box.igs box.brep   a 10 x 20 x 30 box at the origin (volume 6000)
//   cylinder.step               radius 5, height 20 (volume pi r^2 h = 500 pi)
//   assembly.step               two parts, "bracket" red and "shaft" blue (XCAF)
//   inch.step                   a 1 x 2 x 3 inch box, the file's unit inches (volume 6 in^3)
// usage: occtgen DIR. Built by the Makefile when OCCT's headers are there.
// occtgen --bench DIR N writes plate.step instead: a 10 mm plate with
// N x N holes and a boss on every one, about 1 MB at N = 16
// (tools/bench-step.sh, make bench-step). occtgen --dag DIR N writes
// dag.step: N assemblies, each two instances of the next, a box placed
// 2^N times in a file of some 50 KB (OCCT's writer takes time 2^N too:
// 1.7 s at N = 14 on a loaded machine, 20 s at 18), a hostile file for
// the shim's bound on placed parts.

#include <cstdio>
#include <cstdlib>
#include <string>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepTools.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Quantity_Color.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

static bool write_step(const TopoDS_Shape &s, const std::string &path, const char *unit)
{
    STEPControl_Writer w;
    if (unit)
        Interface_Static::SetCVal("write.step.unit", unit);
    bool ok = w.Transfer(s, STEPControl_AsIs) == IFSelect_RetDone && w.Write(path.c_str()) == IFSelect_RetDone;
    Interface_Static::SetCVal("write.step.unit", "MM");
    return ok;
}

static bool write_iges(const TopoDS_Shape &s, const std::string &path)
{
    IGESControl_Writer w("MM", 1);   // BRep mode: the solid as MSBO
    if (!w.AddShape(s))
        return false;
    w.ComputeModel();
    return w.Write(path.c_str());
}

static TDF_Label add_part(const Handle(XCAFDoc_ShapeTool) &st, const Handle(XCAFDoc_ColorTool) &ct,
                          const TopoDS_Shape &s, const char *name, double r, double g, double b)
{
    TDF_Label l = st->AddShape(s, Standard_False);
    TDataStd_Name::Set(l, name);
    ct->SetColor(l, Quantity_Color(r, g, b, Quantity_TOC_sRGB), XCAFDoc_ColorSurf);
    return l;
}

static bool write_assembly(const std::string &path)
{
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    Handle(XCAFDoc_ShapeTool) st = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    Handle(XCAFDoc_ColorTool) ct = XCAFDoc_DocumentTool::ColorTool(doc->Main());
    TDF_Label assy = st->NewShape();
    TDataStd_Name::Set(assy, "machine");
    TDF_Label bracket = add_part(st, ct, BRepPrimAPI_MakeBox(40, 10, 5).Shape(), "bracket", 1, 0, 0);
    TDF_Label shaft = add_part(st, ct, BRepPrimAPI_MakeCylinder(3, 30).Shape(), "shaft", 0, 0, 1);
    gp_Trsf t;
    st->AddComponent(assy, bracket, TopLoc_Location(t));
    t.SetTranslation(gp_Vec(20, 5, 5));
    st->AddComponent(assy, shaft, TopLoc_Location(t));
    st->UpdateAssemblies();
    STEPCAFControl_Writer w;
    w.SetColorMode(true);
    w.SetNameMode(true);
    return w.Transfer(doc, STEPControl_AsIs) && w.Write(path.c_str()) == IFSelect_RetDone;
}

// A plate of n x n holes, each with a ring standing around it: curved
// faces, seams and trimmed planes, as a machined part has.
static bool write_plate(const std::string &path, int n)
{
    double pitch = 12, side = pitch * n + pitch;
    TopoDS_Shape plate = BRepPrimAPI_MakeBox(side, side, 10).Shape();
    TopTools_ListOfShape rings, holes;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            gp_Ax2 at(gp_Pnt(pitch * (i + 1), pitch * (j + 1), 10), gp_Dir(0, 0, 1));
            rings.Append(BRepPrimAPI_MakeCylinder(at, 5, 4).Shape());
            gp_Ax2 down(gp_Pnt(pitch * (i + 1), pitch * (j + 1), -1), gp_Dir(0, 0, 1));
            holes.Append(BRepPrimAPI_MakeCylinder(down, 3, 20).Shape());
        }
    TopTools_ListOfShape args;
    args.Append(plate);
    BRepAlgoAPI_Fuse fuse;
    fuse.SetArguments(args);
    fuse.SetTools(rings);
    fuse.Build();
    if (!fuse.IsDone())
        return false;
    TopTools_ListOfShape body;
    body.Append(fuse.Shape());
    BRepAlgoAPI_Cut cut;
    cut.SetArguments(body);
    cut.SetTools(holes);
    cut.Build();
    return cut.IsDone() && write_step(cut.Shape(), path, NULL);
}

// A hostile assembly: small, and 2^levels parts once its instances are
// followed (a reader must bound the walk).
static bool write_dag(const std::string &path, int levels)
{
    Handle(TDocStd_Document) doc;
    XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
    Handle(XCAFDoc_ShapeTool) st = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    TDF_Label below = st->AddShape(BRepPrimAPI_MakeBox(1, 1, 1).Shape(), Standard_False);
    for (int i = 0; i < levels; i++) {
        TDF_Label a = st->NewShape();
        gp_Trsf t;
        st->AddComponent(a, below, TopLoc_Location(t));
        t.SetTranslation(gp_Vec(0, 0, 2));
        st->AddComponent(a, below, TopLoc_Location(t));
        below = a;
    }
    st->UpdateAssemblies();
    STEPCAFControl_Writer w;
    return w.Transfer(doc, STEPControl_AsIs) && w.Write(path.c_str()) == IFSelect_RetDone;
}

int main(int argc, char **argv)
{
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    STEPControl_Controller::Init();
    IGESControl_Controller::Init();
    if (argc == 4 && std::string(argv[1]) == "--bench") {
        int n = atoi(argv[3]);
        if (n < 1 || n > 200 || !write_plate(std::string(argv[2]) + "/plate.step", n)) {
            fprintf(stderr, "occtgen: the plate could not be written in %s\n", argv[2]);
            return 1;
        }
        return 0;
    }
    if (argc == 4 && std::string(argv[1]) == "--dag") {
        int n = atoi(argv[3]);
        if (n < 1 || n > 40 || !write_dag(std::string(argv[2]) + "/dag.step", n)) {
            fprintf(stderr, "occtgen: the assembly could not be written in %s\n", argv[2]);
            return 1;
        }
        return 0;
    }
    if (argc != 2) {
        fprintf(stderr, "usage: occtgen DIR | occtgen --bench DIR N | occtgen --dag DIR N\n");
        return 2;
    }
    std::string d = std::string(argv[1]) + "/";
    TopoDS_Shape box = BRepPrimAPI_MakeBox(10, 20, 30).Shape();
    TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(5, 20).Shape();
    // OCCT 7.6 writes the coordinates as they are under the unit it is
    // told to name: a 1 x 2 x 3 box in a file that says inches
    TopoDS_Shape inch = BRepPrimAPI_MakeBox(1, 2, 3).Shape();
    bool ok = write_step(box, d + "box.step", NULL) && write_iges(box, d + "box.igs") &&
              BRepTools::Write(box, (d + "box.brep").c_str()) && write_step(cyl, d + "cylinder.step", NULL) &&
              write_step(inch, d + "inch.step", "INCH") && write_assembly(d + "assembly.step");
    if (!ok) {
        fprintf(stderr, "occtgen: a file could not be written in %s\n", argv[1]);
        return 1;
    }
    return 0;
}
