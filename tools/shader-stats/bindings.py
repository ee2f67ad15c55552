#!/usr/bin/env python3
"""Descriptor set 0 of a SPIR-V compute shader, as vkstats reads it: "BINDING KIND" a line.

Reads spirv-cross's reflection (JSON) on standard input: spirv-cross SHADER.spv --reflect | bindings.py
"""
import json
import sys

KINDS = {"ssbos": "ssbo", "images": "image", "textures": "texture", "ubos": "ubo"}
reflection = json.load(sys.stdin)
for key, kind in KINDS.items():
    for resource in reflection.get(key, []):
        if resource.get("set", 0) != 0:
            sys.exit(f"bindings.py: {resource.get('name')} is in set {resource['set']}: vkstats lays out set 0 only")
        print(resource["binding"], kind)
