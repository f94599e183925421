#!/usr/bin/env python3
"""Independent reference for tests/scene/test_points_and_block.cpp: the table acceleration of a
rectangular pulse (duration tp, 1 ms linear ramps at both ends) that just overturns a solid uniform box
W x H (centre of gravity at H/2) rocking on a rigid floor without sliding (Housner's problem, first
excursion), by bisection of a nonlinear 1-DOF rocking integration (RK4, 20 us) about the box's edge,
I_O = m (W^2 + H^2) / 3. Standard library only.

    python3 tests/scene/solid_block_rocking.py W H tp     # prints the threshold, m/s^2
"""
import math,sys
g=9.80665
def tips(W,H,A,tp,ramp=0.001,dt=2e-5,T=6.0):
    b,h=W/2,H/2; R=math.hypot(b,h); al=math.atan2(b,h); m=1.0
    IO=m*(W*W+H*H)/3.0
    def acc(t):
        if t<0: return 0
        if t<ramp: return A*t/ramp
        if t<tp: return A
        if t<tp+ramp: return A*(1-(t-tp)/ramp)
        return 0
    th=0.0; w=0.0; t=0.0
    def f(t,th,w):
        a=acc(t)
        if th<=0 and w<=0 and a*math.cos(al)<=g*math.sin(al): return (0.0,0.0)
        return (w, m*R*(a*math.cos(al-th)-g*math.sin(al-th))/IO)
    while t<T:
        k1=f(t,th,w); k2=f(t+dt/2,th+dt/2*k1[0],w+dt/2*k1[1]); k3=f(t+dt/2,th+dt/2*k2[0],w+dt/2*k2[1]); k4=f(t+dt,th+dt*k3[0],w+dt*k3[1])
        th+=dt/6*(k1[0]+2*k2[0]+2*k3[0]+k4[0]); w+=dt/6*(k1[1]+2*k2[1]+2*k3[1]+k4[1]); t+=dt
        if th<0: return False
        if th>math.pi/2: return True
        if t>tp+0.01 and th<1e-9 and w<=0: return False
    return th>al
def threshold(W,H,tp):
    lo,hi=g*W/H,20*g*W/H
    for _ in range(40):
        mid=0.5*(lo+hi)
        if tips(W,H,mid,tp): hi=mid
        else: lo=mid
    return 0.5*(lo+hi)
W,H,tp=float(sys.argv[1]),float(sys.argv[2]),float(sys.argv[3])
print(threshold(W,H,tp))
