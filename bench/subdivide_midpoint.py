#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# Usage: python3 subdivide_midpoint.py IN.obj OUT.obj ROUNDS (bench/RESULTS.md, "Repair": bunny_1m)
# Midpoint 1-to-4 subdivision, twice (the 1.1M-face test mesh of issue 13).
import sys
V=[];F=[]
for line in open(sys.argv[1]):
    if line.startswith('v '): V.append(tuple(map(float,line.split()[1:4])))
    elif line.startswith('f '):
        idx=[int(t.split('/')[0]) for t in line.split()[1:]]
        idx=[i-1 if i>0 else len(V)+i for i in idx]
        for k in range(1,len(idx)-1): F.append((idx[0],idx[k],idx[k+1]))
for _ in range(int(sys.argv[3])):
    mid={}
    def m(a,b):
        k=(a,b) if a<b else (b,a)
        if k not in mid:
            pa,pb=V[a],V[b]; V.append(tuple((x+y)/2 for x,y in zip(pa,pb))); mid[k]=len(V)-1
        return mid[k]
    G=[]
    for a,b,c in F:
        ab,bc,ca=m(a,b),m(b,c),m(c,a)
        G+= [(a,ab,ca),(ab,b,bc),(ca,bc,c),(ab,bc,ca)]
    F=G
with open(sys.argv[2],'w') as o:
    for p in V: o.write('v %.17g %.17g %.17g\n'%p)
    for t in F: o.write('f %d %d %d\n'%(t[0]+1,t[1]+1,t[2]+1))
print(len(V),len(F))
