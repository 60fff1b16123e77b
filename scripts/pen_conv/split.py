import csv,bisect,sys
def load(arg):
    # FILE:N:rad -> true tip depth and time from true contact (table.py)
    f,N,rad=arg.split(':'); sh=float(rad)*7.38/float(N)
    r=[x for x in csv.reader(open(f)) if len(x)==5][1:]
    return [float(x[0])-sh/1290.0*1e3 for x in r],[float(x[1])-sh for x in r],[float(x[2]) for x in r]
def interp(xs,ys,x):
    i=bisect.bisect(xs,x)
    if i<=0 or i>=len(xs): return float('nan')
    return ys[i-1]+(ys[i]-ys[i-1])*(x-xs[i-1])/(xs[i]-xs[i-1])
a=load(sys.argv[1]); b=load(sys.argv[2]); T=float(sys.argv[3])
# remaining penetration of run a from speed V: P_end_a - P_a(t where V_a = V)
Pend_a=max(a[1]); Pend_b=max(b[1])
Va_T=interp(a[0],a[2],T); Vb_T=interp(b[0],b[2],T)
# time in a where V = Vb_T (V decreasing): search
ts=a[0]; vs=a[2]
k=next(i for i in range(len(vs)) if vs[i]<=Vb_T)
t_star=ts[k-1]+(ts[k]-ts[k-1])*(vs[k-1]-Vb_T)/(vs[k-1]-vs[k])
rem_a_from_Vb=Pend_a-interp(a[0],a[1],t_star)
print("T=%g: Va=%.1f Vb=%.1f Pa=%.3f Pb=%.3f ; Pmax a=%.3f b=%.3f (diff %.3f)"%(T,Va_T,Vb_T,interp(a[0],a[1],T),interp(b[0],b[1],T),Pend_a,Pend_b,Pend_b-Pend_a))
est=interp(b[0],b[1],T)+rem_a_from_Vb
print("b's state at T continued with a's resistance: Pmax=%.3f -> part from state at T: %.3f, part after T: %.3f"%(est,est-Pend_a,Pend_b-est))
