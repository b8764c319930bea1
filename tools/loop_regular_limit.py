#!/usr/bin/env python3
"""Checks the closed forms of Loop's limit at a regular vertex's child and a regular edge's child
(DEVELOPERS.md, "Loop's regular limit in closed form from the level before") against the CLI's
limit positions and normals.

    subsurf --scheme loop --levels 1 --ignore-uv MESH.obj -o l1.obj
    subsurf --scheme loop --levels 2 --ignore-uv --limit MESH.obj -o l2.obj
    python3 tools/loop_regular_limit.py l1.obj l2.obj

Triangle meshes only. Edge children are matched to the level-2 points by position.
"""
import math, sys
def read(path):
    V=[];F=[];N=[]
    for line in open(path):
        if line.startswith('v '): V.append(tuple(map(float,line.split()[1:4])))
        elif line.startswith('vn '): N.append(tuple(map(float,line.split()[1:4])))
        elif line.startswith('f '): F.append(tuple(int(t.split('/')[0])-1 for t in line.split()[1:]))
    return V,F,N
V,F,_=read(sys.argv[1])
L,_,LN=read(sys.argv[2])
third={}
for (a,b,c) in F:
    third[(a,b)]=c; third[(b,c)]=a; third[(c,a)]=b
out={}
for (a,b) in third: out.setdefault(a,b)
def ring(v):
    q0=out[v]; r=[q0]; q=q0
    for _ in range(12):
        q=third.get((v,q))
        if q is None: return None
        if q==q0: return r
        r.append(q)
    return None
add=lambda *p: tuple(sum(x) for x in zip(*p))
sub=lambda p,q: tuple(x-y for x,y in zip(p,q))
mul=lambda s,p: tuple(s*x for x in p)
def cross(a,b): return (a[1]*b[2]-a[2]*b[1],a[2]*b[0]-a[0]*b[2],a[0]*b[1]-a[1]*b[0])
def unit(a):
    l=math.sqrt(sum(x*x for x in a)); return tuple(x/l for x in a)
def ang(a,b): return math.acos(max(-1,min(1,sum(x*y for x,y in zip(a,b)))))
worst=[0,0,0,0]; cnt=[0,0]
rings={}
for v in range(len(V)):
    r=ring(v)
    if r is None or len(r)!=6: continue
    rings[v]=r
    q=[V[i] for i in r]
    P=mul(1/12,add(mul(6,V[v]),*q))
    d=[sub(q[k],q[k+3]) for k in range(3)]
    t1=add(mul(2,d[0]),d[1],mul(-1,d[2])); t2=add(d[1],d[2])
    n=unit(cross(t1,t2))
    worst[0]=max(worst[0],max(abs(x-y) for x,y in zip(P,L[v]))); worst[1]=max(worst[1],ang(n,LN[v])); cnt[0]+=1
# edge-type: match by position
key=lambda p: tuple(round(x,5) for x in p)
idx={}
for i,p in enumerate(L): idx.setdefault(key(p),i)
miss=0
for (a,b),c in third.items():
    if a>b or a not in rings or b not in rings: continue
    d=third[(b,a)]
    ra=rings[a]; k=ra.index(b); ra=ra[k:]+ra[:k]   # [b,c,a2,a3,a4,d]
    rb=rings[b]; k=rb.index(a); rb=rb[k:]+rb[:k]   # [a,d,b2,b3,b4,c]
    assert ra[1]==c and ra[5]==d and rb[1]==d and rb[5]==c
    A,B,C,D=V[a],V[b],V[c],V[d]; a2,a3,a4=(V[i] for i in ra[2:5]); b2,b3,b4=(V[i] for i in rb[2:5])
    P=mul(1/192,add(mul(63,add(A,B)),mul(26,add(C,D)),mul(3,add(a2,a4,b2,b4)),a3,b3))
    t1=add(mul(13,sub(A,B)),mul(2,sub(add(a2,a4),add(b2,b4))),sub(a3,b3))
    t2=add(mul(6,sub(D,C)),sub(a4,a2),sub(b2,b4))
    n=unit(cross(t1,t2))
    i=idx.get(key(P))
    if i is None: miss+=1; continue
    worst[2]=max(worst[2],max(abs(x-y) for x,y in zip(P,L[i]))); worst[3]=max(worst[3],ang(n,LN[i])); cnt[1]+=1
print('vertex-type',cnt[0],'max |dP|',worst[0],'max normal angle',worst[1])
print('edge-type',cnt[1],'max |dP|',worst[2],'max normal angle',worst[3],'unmatched',miss)
print('level-2 points',len(L),'covered',(cnt[0]+cnt[1])/len(L))
