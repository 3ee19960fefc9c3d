# Does a multistep method that carries its history across tick-held input jumps keep its order?
# Ship roll damper (14.8)-like plant with the active ship scene's numbers, command held per tick (1 ms)
# from a noisy roll-rate measurement, one tick of latency. Methods: RK4 restarted each tick (1 step/tick),
# AB4 across ticks with (a) the derivative history as evaluated, (b) the history's input part replaced by
# the current held input (input-affine). Reference: RK4 at tick/16.
import math, random
A=3.2e7; c=1.1772e7; d1=1.94e6; B=1.5e4; q=1350.0; H=1.018e6
E0=3e5; w=0.63; k=1.018e6; dp=8.36e4; lim=2e5
h=1e-3; T=30.0; N=int(T/h)
def g(t,x):  # input-free part
    ph,be,dph,dbe=x
    cb=math.cos(be)
    return [dph,dbe,(-c*math.sin(ph)-d1*dph-H*cb*dbe+E0*math.cos(w*t))/A,(H*cb*dph-q*math.sin(be)-dp*dbe)/B]
def G(u): return [0.0,0.0,0.0,u/B]
def f(t,x,u):
    a=g(t,x); b=G(u); return [a[i]+b[i] for i in range(4)]
def rk4(t,x,u,hh):
    k1=f(t,x,u); k2=f(t+hh/2,[x[i]+hh/2*k1[i] for i in range(4)],u)
    k3=f(t+hh/2,[x[i]+hh/2*k2[i] for i in range(4)],u); k4=f(t+hh,[x[i]+hh*k3[i] for i in range(4)],u)
    return [x[i]+hh/6*(k1[i]+2*k2[i]+2*k3[i]+k4[i]) for i in range(4)]
def inputs(noise, seed=1):
    # commands from a reference closed loop (RK4 tick/16), recorded, then replayed open loop by every method
    rng=random.Random(seed); x=[0.0]*4; us=[]; pending=0.0
    for n in range(N):
        u=pending
        meas=x[2]+noise*rng.gauss(0,1)
        pending=max(-lim,min(lim,-k*meas))
        us.append(u)
        for s in range(16): x=rk4(n*h+s*h/16,x,u,h/16)
    return us
def run_rk4(us,sub=1):
    x=[0.0]*4; out=[]
    for n in range(N):
        for s in range(sub): x=rk4(n*h+s*h/sub,x,us[n],h/sub)
        out.append(x[0])
    return out
b4=[55/24,-59/24,37/24,-9/24]
def run_ab4(us,affine):
    x=[0.0]*4; out=[]; hist=[]  # entries (g_j, x_j)
    for n in range(N):
        t=n*h
        gj=g(t,x)
        hist.insert(0,gj); hist=hist[:4]
        if len(hist)<4:
            x=rk4(t,x,us[n],h)
        else:
            u=us[n]
            if affine:   # history of g plus the current input's part
                F=[[hj[i]+G(u)[i] for i in range(4)] for hj in hist]
            else:        # history of f as the plant saw it
                F=[[hist[m][i]+G(us[n-m])[i] for i in range(4)] for m in range(4)]
            x=[x[i]+h*sum(b4[m]*F[m][i] for m in range(4)) for i in range(4)]
        out.append(x[0])
    return out
for noise in (0.0, 1e-4/math.sqrt(h)):
    us=inputs(noise)
    ref=run_rk4(us,16)
    for name,o in (("rk4 tick/1",run_rk4(us,1)),("ab4 history as seen",run_ab4(us,False)),("ab4 input-affine",run_ab4(us,True))):
        print(f"noise {noise:.2e}  {name:22s} max|dphi| = {max(abs(a-b) for a,b in zip(o,ref)):.2e}   (|phi|max {max(abs(v) for v in ref):.2e})")
