#!/usr/bin/env python3
# The points of tests/data/references/cornell_near_blocks_points.txt: python3 tests/data/references/cornell_near_blocks_points.py > that file.
import random, math
random.seed(7)
blocks = {'short': ([(130,65),(290,114),(240,272),(82,225)],165), 'tall': ([(423,247),(472,406),(314,456),(265,296)],330)}
print("# Points within 50 mm of the Cornell box's blocks (scenes/cornell.json), seed 7: on the floor 1 to 50 mm")
print("# outside each block's footprint (distance log-uniform, along its perimeter uniformly, corners avoided")
print("# by 2 mm), and on each block's sides 1 to 50 mm above the floor. Made by tests/data/references/cornell_near_blocks_points.py.")

def perimeter_point(edges, lens, cx, cz):
    """A point on the footprint's perimeter (uniform by length, 2 mm from corners), its outward normal."""
    s=random.uniform(0,sum(lens)); i=0
    while s>lens[i]: s-=lens[i]; i+=1
    s=min(max(s,2),lens[i]-2)
    (ax,az),(bx,bz)=edges[i]; t=s/lens[i]
    px,pz=ax+t*(bx-ax),az+t*(bz-az)
    nx,nz=(bz-az)/lens[i],-(bx-ax)/lens[i]
    if nx*(px-cx)+nz*(pz-cz)<0: nx,nz=-nx,-nz
    return px,pz,nx,nz

def log_uniform():
    """1 to 50 mm, log-uniform."""
    return math.exp(random.uniform(math.log(1),math.log(50)))

for name,(fp,h) in blocks.items():
    cx=sum(p[0] for p in fp)/4; cz=sum(p[1] for p in fp)/4
    edges=[(fp[i],fp[(i+1)%4]) for i in range(4)]
    lens=[math.dist(a,b) for a,b in edges]
    for k in range(60):
        px,pz,nx,nz=perimeter_point(edges,lens,cx,cz); d=log_uniform()
        print(f"{px+nx*d:.4f} 0 {pz+nz*d:.4f} 0 1 0 {name}_floor_d{d:.1f}")
    for k in range(20):
        px,pz,nx,nz=perimeter_point(edges,lens,cx,cz); y=log_uniform()
        print(f"{px:.4f} {y:.4f} {pz:.4f} {nx:.6f} 0 {nz:.6f} {name}_side_h{y:.1f}")
