// Soft pneumatic bellows actuator with its tip block: parametric geometry and
// mesh for gmsh (OpenCASCADE kernel). All lengths in mm.
//
// The silicone body is a solid of revolution about the x axis (the actuator
// axis; the base is clamped at x = XBase and the actuator hangs from it, so
// gravity points along +x). Its section in the (x, r) half plane is a closed
// polygon built below from a handful of design numbers; it reproduces the
// reference section shared/paper/actuator_section.csv (kept beside the
// project, not in it) and meshes/check_geometry.py measures how closely.
//
// How the reference section decomposes. Each convolution is a wall of
// constant thickness folded around a mid-surface made of circular arcs of one
// bend radius (FoldRadius) at the crests and valleys, joined by straight
// flanks tangent to both arcs. The cavity side of the wall is that mid-surface
// offset inwards by half the wall thickness, the outer side offset outwards.
// Hence four roundings: cavity valleys and outer crests have the radius
// FoldRadius + WallThickness/2, cavity crests and outer valleys
// FoldRadius - WallThickness/2. In the reference polygon every rounding is
// sampled by a few chords, which makes the flat tops of the outer crests
// (r = 18.62) and the short flats at the cavity crests and outer valleys; the
// chord counts are parameters too. Drawing the roundings as exact arcs instead
// (many chords) adds about 4 % of silicone, mostly at the outer crests, and
// would no longer match the reference's body volume of 67,483 mm^3, which is
// the polygon's.
//
// Usage (generate_meshes.sh holds the options of every committed mesh):
//   gmsh bellows.geo -3 -nt 1 -format msh22 -setnumber Model 1 \
//        -setnumber ElementSize 5 -o bellows_quarter.msh
// and, to write the section polygon without meshing (check_geometry.py):
//   gmsh bellows.geo -0 -setnumber ExportSection 1 -setstring SectionFile f.csv
// Errors, including those of the checks in this file, go to gmsh's log;
// gmsh still exits with 0, so scripts must look for lines "Error".

SetFactory("OpenCASCADE");

// @sect3{Choices made on the command line}
DefineConstant[
  // How many quarters of the body are meshed: 1 = quarter model (y >= 0,
  // z >= 0, symmetry planes y = 0 and z = 0; vertical oscillation), 2 = half
  // model (z >= 0, symmetry plane z = 0; planar pendulum in the x-y plane),
  // 4 = full model (spherical pendulum). The section is revolved by
  // Model * 90 degrees from the x-y plane towards +z.
  Model = {1, Choices{1 = "quarter", 2 = "half", 4 = "full"},
           Name "Parameters/Model (quarters of the body)"},
  // Characteristic (largest) element edge length.
  ElementSize = {5.0, Name "Parameters/Element size (mm)"},
  // Fewest nodes on a full circle (gmsh's Mesh.MinimumCirclePoints, scaled
  // down for arcs). It sets the mesh at the small radii (inlet channel,
  // valleys, necks) once ElementSize is large; the coarse full model needs 5
  // instead of gmsh's 7 to come near the reference study's element count.
  CircleNodes = {7, Name "Parameters/Minimum nodes per circle"},
  // gmsh's surface mesher (Mesh.Algorithm): 1 MeshAdapt, 5 Delaunay, 6
  // Frontal-Delaunay. The surface mesh decides whether the thin walls get
  // flat tetrahedra, and which mesher does best varies from mesh to mesh, so
  // generate_meshes.sh fixes it per mesh.
  SurfaceAlgorithm = {6, Choices{1, 5, 6}, Name "Parameters/Surface mesher"},
  // 1: linear tetrahedra. 2: 10-node tetrahedra, whose mid-edge nodes gmsh
  // places on the curved surfaces (the program reads them as a curved
  // geometry, include/core/curved_geometry.h).
  ElementOrder = {1, Choices{1, 2}, Name "Parameters/Element order"},
  // The tip block: 0 the study's box; 1 a cylinder of the same length,
  // mass, centre of mass and tensor of inertia (radius BlockWidth /
  // sqrt(3), see include/core/bellows_mesh.h), the block of the program's
  // hexahedral mesh, here to measure what the block's shape changes.
  BlockShape = {0, Choices{0 = "box", 1 = "cylinder"}, Name "Parameters/Tip block"},
  // Write the section polygon as "x,r" lines to SectionFile and stop
  // before building any solid (used by check_geometry.py).
  ExportSection = {0, Choices{0, 1}, Name "Parameters/Export section"},
  SectionFile = {"bellows_section.csv", Name "Parameters/Section file"}
];

// @sect3{Design parameters of the silicone body (mm)}

// Clamped base face; the body extends towards +x from here.
XBase = -15.25;
// Axial length of the inlet channel, from the base face to the bottom of the
// first cavity valley, and equally the thickness of the closed end cap, from
// the bottom of the last cavity valley to the end face.
EndWall = 6.0;
// Radius of the inlet channel. The channel runs straight into the first
// cavity valley, so this is also the radius of the bottoms of all cavity
// valleys (the smallest radius of the cavity).
InletRadius = 2.5;
// Outer radius of the base ring and of the end cap.
RingRadius = 14.5;
// The outer flanks of the first and the last convolution stop at this radius
// and a neck of this axial length joins them to the base ring and to the cap.
NeckRadius = 7.0;
NeckLength = 1.0;

// The convolutions.
NumConvolutions = 10;
Pitch = 9.25;
// Apex radius of the cavity at the crests (largest radius of the cavity's
// exact roundings; the chords cut it to 15.78).
InnerCrestRadius = 16.0;
WallThickness = 3.0;
// Bend radius of the wall's mid-surface at crests and valleys.
FoldRadius = 1.75;
// Chords per rounding, each over the rounding's full angle (about 167 deg).
// An even count puts a vertex at the bottom of a cavity valley, which the
// half valleys at both ends need; the others may be odd.
ChordsCavityValley = 4;
ChordsCavityCrest = 1;
ChordsOuterCrest = 3;
ChordsOuterValley = 1;

// @sect3{The tip block}
// A rectangular block glued over the end cap, centred on the axis: the 3D
// printed holder with the steel mass. Its square face of side BlockWidth
// covers the cap's end disc of radius RingRadius; as BlockWidth = 2 *
// RingRadius the disc touches the square's edges at four points.
BlockLength = 10.0;
BlockWidth = 29.0;

// @sect3{Derived quantities}
// Radii of the two roundings (see the head of the file).
SmallRounding = FoldRadius - WallThickness / 2;  // cavity crests, outer valleys
LargeRounding = FoldRadius + WallThickness / 2;  // cavity valleys, outer crests
// The centres of all roundings of a crest lie at radius CrestCentreRadius, those
// of a valley at ValleyCentreRadius.
CrestCentreRadius = InnerCrestRadius - SmallRounding;
ValleyCentreRadius = InletRadius + LargeRounding;
HalfPitch = Pitch / 2;
XFirstValley = XBase + EndWall;
XLastValley = XFirstValley + NumConvolutions * Pitch;
XEnd = XLastValley + EndWall;

// The flank. The mid-surface line is the internal common tangent of the crest
// circle (centre (c, CrestCentreRadius)) and the next valley circle (centre
// (c + HalfPitch, ValleyCentreRadius)), both of radius FoldRadius. With u the
// unit vector from the crest centre to the valley centre and D their distance,
// the unit normal N of the flank satisfies N.u = 2 FoldRadius / D; N points
// from the crest centre to the tangent point on the descending flank, and
// FlankAngle is its angle to the x axis (6.3 deg: the flanks lean 6.3 deg from
// the radial direction, making the folds taper outwards).
CentreDistance = Sqrt(HalfPitch^2 + (CrestCentreRadius - ValleyCentreRadius)^2);
If (2 * FoldRadius >= CentreDistance || SmallRounding <= 0)
  Error("bellows.geo: FoldRadius and WallThickness leave no straight flank");
  Abort;
EndIf
UX = HalfPitch / CentreDistance;
UR = -(CrestCentreRadius - ValleyCentreRadius) / CentreDistance;
SinB = 2 * FoldRadius / CentreDistance;
CosB = Sqrt(1 - SinB^2);
NX = SinB * UX - CosB * UR;
NR = SinB * UR + CosB * UX;
FlankAngle = Atan2(NR, NX);

// The necks: where the outer flank of the first convolution rises through
// NeckRadius. That flank runs from the tangent point on the outer valley
// rounding left of the first crest to the tangent point on the first outer crest.
XFirstCrest = XFirstValley + HalfPitch;
FlankLowX = XFirstValley + SmallRounding * NX;
FlankLowR = ValleyCentreRadius - SmallRounding * NR;
FlankHighX = XFirstCrest - LargeRounding * NX;
FlankHighR = CrestCentreRadius + LargeRounding * NR;
If (NeckRadius <= FlankLowR || NeckRadius >= FlankHighR)
  Error("bellows.geo: NeckRadius must lie on the straight outer flank");
  Abort;
EndIf
XNeckFirst = FlankLowX + (NeckRadius - FlankLowR) * (FlankHighX - FlankLowX)
                         / (FlankHighR - FlankLowR);
// The last convolution mirrors the first about the body's middle.
XNeckLast = XFirstValley + XLastValley - XNeckFirst;

// @sect3{The section polygon}
// Vertices in counter-clockwise order in the (x, r) plane: along the cavity
// from the base to the end cap (CavX/CavR, x increasing), across the end face,
// then back along the outer surface (OutX/OutR, built with x increasing and
// appended reversed). NumCavityVertices remembers where the cavity ends, so
// that the cavity faces can be told from the outer ones after revolving.
Eps = 1e-9;
CavX[] = {XBase, XFirstValley};
CavR[] = {InletRadius, InletRadius};
For k In {0 : NumConvolutions}
  XValley = XFirstValley + k * Pitch;
  // Rounding of a cavity valley: angles from Pi + FlankAngle (left flank)
  // through 3 Pi/2 (bottom) to 2 Pi - FlankAngle (right flank); the half
  // valleys at both ends keep only their inner half and their bottom.
  For j In {0 : ChordsCavityValley}
    Angle = Pi + FlankAngle + j * (Pi - 2 * FlankAngle) / ChordsCavityValley;
    Keep = 1;
    If (k == 0 && Angle <= 3 * Pi / 2 + Eps)
      Keep = 0;
    EndIf
    If (k == NumConvolutions && Angle >= 3 * Pi / 2 - Eps)
      Keep = 0;
    EndIf
    If (Keep)
      CavX[] += {XValley + LargeRounding * Cos(Angle)};
      CavR[] += {ValleyCentreRadius + LargeRounding * Sin(Angle)};
    EndIf
  EndFor
  If (k < NumConvolutions)
    // Rounding of a cavity crest: angles from Pi - FlankAngle down to FlankAngle.
    For j In {0 : ChordsCavityCrest}
      Angle = Pi - FlankAngle - j * (Pi - 2 * FlankAngle) / ChordsCavityCrest;
      CavX[] += {XValley + HalfPitch + SmallRounding * Cos(Angle)};
      CavR[] += {CrestCentreRadius + SmallRounding * Sin(Angle)};
    EndFor
  EndIf
EndFor
CavX[] += {XLastValley};
CavR[] += {InletRadius};
NumCavityVertices = #CavX[];

OutX[] = {XNeckFirst - NeckLength, XNeckFirst - NeckLength, XNeckFirst};
OutR[] = {RingRadius, NeckRadius, NeckRadius};
For k In {0 : NumConvolutions - 1}
  XCrest = XFirstCrest + k * Pitch;
  For j In {0 : ChordsOuterCrest}
    Angle = Pi - FlankAngle - j * (Pi - 2 * FlankAngle) / ChordsOuterCrest;
    OutX[] += {XCrest + LargeRounding * Cos(Angle)};
    OutR[] += {CrestCentreRadius + LargeRounding * Sin(Angle)};
  EndFor
  If (k < NumConvolutions - 1)
    For j In {0 : ChordsOuterValley}
      Angle = Pi + FlankAngle + j * (Pi - 2 * FlankAngle) / ChordsOuterValley;
      OutX[] += {XCrest + HalfPitch + SmallRounding * Cos(Angle)};
      OutR[] += {ValleyCentreRadius + SmallRounding * Sin(Angle)};
    EndFor
  EndIf
EndFor
OutX[] += {XNeckLast, XNeckLast + NeckLength, XNeckLast + NeckLength};
OutR[] += {NeckRadius, NeckRadius, RingRadius};

// Assemble: cavity, the cavity's closing disc down to the axis, along the axis
// through the cap, up the end face, the outer surface backwards, the base face.
SecX[] = CavX[];
SecR[] = CavR[];
SecX[] += {XLastValley, XEnd, XEnd};
SecR[] += {0, 0, RingRadius};
For i In {#OutX[] - 1 : 0 : -1}
  SecX[] += {OutX[i]};
  SecR[] += {OutR[i]};
EndFor
SecX[] += {XBase};
SecR[] += {RingRadius};
NumSectionVertices = #SecX[];

If (ExportSection)
  Printf("# section of bellows.geo: x_mm,r_mm (closed polygon, counter-clockwise)") > SectionFile;
  For i In {0 : NumSectionVertices - 1}
    Printf("%.9f,%.9f", SecX[i], SecR[i]) >> SectionFile;
  EndFor
  Exit;
EndIf

// @sect3{The silicone body}
// The section lies in the x-y plane (y = r >= 0, z = 0). Line i joins vertex
// i to vertex i+1; lines 0 .. NumCavityVertices-1 are the cavity (the last
// of them closes the cavity at x = XLastValley), line NumCavityVertices runs
// along the axis, line NumCavityVertices+1 is the end face and the last line
// is the base face.
For i In {0 : NumSectionVertices - 1}
  SectionPoint[i] = newp;
  Point(SectionPoint[i]) = {SecX[i], SecR[i], 0};
EndFor
For i In {0 : NumSectionVertices - 1}
  SectionLine[i] = newl;
  Line(SectionLine[i]) = {SectionPoint[i], SectionPoint[(i + 1) % NumSectionVertices]};
EndFor
AxisLine = SectionLine[NumCavityVertices];
EndFaceLine = SectionLine[NumCavityVertices + 1];
BaseLine = SectionLine[NumSectionVertices - 1];
SectionLoop = newll;
Curve Loop(SectionLoop) = {SectionLine[]};
Section = news;
Plane Surface(Section) = {SectionLoop};

// Revolving about the x axis from +y towards +z. The quarter and half models
// are revolved through 90 and 180 degrees rather than cut from the full body
// with boxes: the solid is the same, the symmetry faces are copies of the
// plane section, and no boolean operation touches the curved faces. The
// curve on the axis sweeps no face (OpenCASCADE collapses it into the axis,
// and the cap closes there without a degenerate face). The result lists the
// rotated section (or, for a full turn, the section itself), the volume and
// one lateral face per boundary curve of the section in the order of
// Boundary{}, skipping the curve on the axis.
Revolved[] = Extrude {{1, 0, 0}, {0, 0, 0}, Model * Pi / 2} { Surface{Section}; };
Body = Revolved[1];
SectionCurves[] = Abs(Boundary{ Surface{Section}; });
NextLateral = 2;
CavityFaces[] = {};
For i In {0 : #SectionCurves[] - 1}
  Edge = SectionCurves[i];
  If (Edge != AxisLine)
    FaceOfLine~{Edge} = Revolved[NextLateral];
    NextLateral += 1;
  EndIf
EndFor
For i In {0 : NumCavityVertices - 1}
  CavityFaces[] += {FaceOfLine~{SectionLine[i]}};
EndFor
BaseFace = FaceOfLine~{BaseLine};
EndFace = FaceOfLine~{EndFaceLine};
If (Model == 4)
  // A full turn leaves the section as a loose face inside the seam.
  Delete { Surface{Section}; }
EndIf

// Guard against a change in gmsh's ordering: the face swept by cavity line i
// must span that line's x range and reach its larger radius.
For i In {0 : NumCavityVertices - 1}
  Extent[] = BoundingBox Surface{CavityFaces[i]};
  Ends[] = {SecX[i], SecX[i + 1], SecR[i], SecR[i + 1]};
  If (Fabs(Extent[0] - Min(Ends[0], Ends[1])) > 1e-6 ||
      Fabs(Extent[3] - Max(Ends[0], Ends[1])) > 1e-6 ||
      Fabs(Extent[4] - Max(Ends[2], Ends[3])) > 1e-6)
    Error("bellows.geo: cavity face %g does not match section line %g", CavityFaces[i], i);
    Abort;
  EndIf
EndFor

// @sect3{The tip block and the glued joint}
// The block is cut to the same part of the cross-section as the body. The
// fragments make one conforming model: the cap's end disc becomes a face
// shared by both volumes, and the block's face at x = XEnd is split into that
// disc and the rest. With BlockWidth = 2 RingRadius the disc touches the
// square's edges, so the rest of the square ends in cusps at four points (two
// in the quarter model, at its corners); gmsh meshes them without trouble
// (the tetrahedra there have gamma >= 0.37 in the coarse meshes).
RecordedFaces[] = {CavityFaces[], BaseFace, EndFace};
RecordedBoxes[] = {};
For i In {0 : #RecordedFaces[] - 1}
  RecordedBoxes[] += BoundingBox Surface{RecordedFaces[i]};
EndFor
HalfWidth = BlockWidth / 2;
If (BlockShape == 0)
  TipBlock = newv;
  If (Model == 1)
    Box(TipBlock) = {XEnd, 0, 0, BlockLength, HalfWidth, HalfWidth};
  ElseIf (Model == 2)
    Box(TipBlock) = {XEnd, -HalfWidth, 0, BlockLength, BlockWidth, HalfWidth};
  Else
    Box(TipBlock) = {XEnd, -HalfWidth, -HalfWidth, BlockLength, BlockWidth, BlockWidth};
  EndIf
Else
  // The cylinder, revolved like the body from its rectangular section.
  BlockSection = news;
  Rectangle(BlockSection) = {XEnd, 0, 0, BlockLength, BlockWidth / Sqrt(3)};
  BlockRevolved[] = Extrude {{1, 0, 0}, {0, 0, 0}, Model * Pi / 2} { Surface{BlockSection}; };
  TipBlock = BlockRevolved[1];
  If (Model == 4)
    Delete { Surface{BlockSection}; }
  EndIf
EndIf
BooleanFragments{ Volume{Body}; Delete; }{ Volume{TipBlock}; Delete; }

Far = 1e3;
Tol = 1e-6;
BodyVolumes[] = Volume In BoundingBox{XBase - Tol, -Far, -Far, XEnd + Tol, Far, Far};
BlockVolumes[] = Volume In BoundingBox{XEnd - Tol, -Far, -Far, XEnd + BlockLength + Tol, Far, Far};
If (#BodyVolumes[] != 1 || #BlockVolumes[] != 1)
  Error("bellows.geo: expected one body and one block after the fragments");
  Abort;
EndIf
// @sect3{Boundary classification}
BodyFaces[] = Abs(Boundary{ Volume{BodyVolumes[0]}; });
// The fragments renumber faces, so the cavity, base and end faces are found
// again by their bounding boxes recorded above, which do not change.
For i In {0 : #RecordedFaces[] - 1}
  Matches[] = {};
  For k In {0 : #BodyFaces[] - 1}
    Extent[] = BoundingBox Surface{BodyFaces[k]};
    Same = 1;
    For m In {0 : 5}
      If (Fabs(Extent[m] - RecordedBoxes[6 * i + m]) > Tol)
        Same = 0;
      EndIf
    EndFor
    If (Same)
      Matches[] += {BodyFaces[k]};
    EndIf
  EndFor
  If (#Matches[] != 1)
    Error("bellows.geo: %g faces match recorded face %g", #Matches[], i);
    Abort;
  EndIf
  RecordedFaces[i] = Matches[0];
EndFor
CavityFaces[] = RecordedFaces[{0 : NumCavityVertices - 1}];
BaseFace = RecordedFaces[NumCavityVertices];
EndFace = RecordedFaces[NumCavityVertices + 1];
BlockFaces[] = Abs(Boundary{ Volume{BlockVolumes[0]}; });
SymmetryY[] = {};
If (Model == 1)
  SymmetryY[] = Surface In BoundingBox{-Far, -Tol, -Far, Far, Tol, Far};
EndIf
SymmetryZ[] = {};
If (Model < 4)
  SymmetryZ[] = Surface In BoundingBox{-Far, -Far, -Tol, Far, Far, Tol};
EndIf
// The glued joint is the face the two volumes share; it is interior and gets
// no tag. Everything on the block that is neither joint nor symmetry plane is
// its outer surface; everything on the body that is none of base, cavity,
// joint or symmetry plane is the outer silicone surface.
Joint[] = {};
For i In {0 : #BlockFaces[] - 1}
  For k In {0 : #BodyFaces[] - 1}
    If (BlockFaces[i] == BodyFaces[k])
      Joint[] += {BlockFaces[i]};
    EndIf
  EndFor
EndFor
If (#Joint[] != 1 || Joint[0] != EndFace)
  Error("bellows.geo: the joint should be the end disc of the cap only");
  Abort;
EndIf
BlockOuter[] = BlockFaces[];
BlockOuter[] -= {Joint[], SymmetryY[], SymmetryZ[]};
BodyOuter[] = BodyFaces[];
BodyOuter[] -= {Joint[], SymmetryY[], SymmetryZ[], BaseFace, CavityFaces[]};

// @sect3{Physical groups}
// Material ids (volumes) and boundary ids (surfaces) as the program expects
// them; every boundary face carries one, the joint none.
Physical Volume("silicone", 1) = {BodyVolumes[]};
Physical Volume("tip_block", 2) = {BlockVolumes[]};
Physical Surface("base", 1) = {BaseFace};
Physical Surface("cavity", 2) = {CavityFaces[]};
If (#SymmetryY[])
  Physical Surface("symmetry_y", 3) = {SymmetryY[]};
EndIf
If (#SymmetryZ[])
  Physical Surface("symmetry_z", 4) = {SymmetryZ[]};
EndIf
Physical Surface("block_outer", 5) = {BlockOuter[]};
Physical Surface("silicone_outer", 6) = {BodyOuter[]};

// @sect3{Mesh options}
// Linear tetrahedra unless ElementOrder = 2 (the program raises the order
// of the displacement itself; second-order nodes only curve the geometry).
// Curving the edges of a thin wall's tetrahedra can invert one; gmsh's
// elastic analogy followed by its optimizer (HighOrderOptimize 2) untangles
// the meshes of generate_meshes.sh, which checks it. One largest
// size everywhere, single-threaded; the geometry's own short edges (the 0.5 mm chords at the
// cavity crests and outer valleys, the 1 mm necks) refine the mesh locally by
// themselves. Below ElementSize = 12 the section's vertices, not the size,
// govern the count. gmsh's Delaunay mesher (Algorithm3D 1) is used because it
// gives the same mesh on every run; HXT (10) leaves fewer flat tetrahedra in
// the crests of the coarse meshes but differs from run to run even on one
// thread. Written as MSH 2.2 ASCII with only the physical groups, which is
// what deal.II's GridIn::read_msh reads.
Mesh.ElementOrder = ElementOrder;
Mesh.HighOrderOptimize = 2;
Mesh.MeshSizeMax = ElementSize;
Mesh.MeshSizeMin = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MinimumCirclePoints = CircleNodes;
Mesh.Algorithm = SurfaceAlgorithm;
Mesh.Algorithm3D = 1;
Mesh.Optimize = 1;
General.NumThreads = 1;
Mesh.MshFileVersion = 2.2;
Mesh.Binary = 0;
Mesh.SaveAll = 0;
