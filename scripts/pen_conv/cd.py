import csv,bisect,sys
M=3.89349e-13; rho=1030; A=3.14159*(3.69e-6)**2
def load(f):
    r=list(csv.reader(open(f)))[1:]
    r=[x for x in r if len(x)==5]
    return [float(x[0]) for x in r],[float(x[2]) for x in r],[float(x[1]) for x in r]
def V(d,t):
    i=bisect.bisect(d[0],t)
    if i>=len(d[0]) or i==0: return float('nan')
    t0,t1=d[0][i-1],d[0][i]; return d[1][i-1]+(d[1][i]-d[1][i-1])*(t-t0)/(t1-t0)
fs=sys.argv[1:]
ds=[load(f) for f in fs]
w=[0,2,5,10,20,35,50,75,100,125,150,175,200,225]
print("window  " + "  ".join("Vmid  Ceff  R=F/A-0.5rhoCV2" for f in fs))
for a,b in zip(w[:-1],w[1:]):
    row=[]
    for d in ds:
        va,vb=V(d,a if a>0 else 0.01),V(d,b)
        F=M*(va-vb)/((b-a)*1e-9); vm=0.5*(va+vb)
        row.append("%6.0f %5.3f %6.1fMPa"%(vm, F/(0.5*rho*vm*vm*A), (F/A-0.5*rho*0.375*vm*vm)/1e6))
    print("%3d-%3d "%(a,b)+"  ".join(row))
