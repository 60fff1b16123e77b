# final table: true-tip depth P = P_driver - rad*dx1, t from true contact t - rad*dx1/v0
import csv,bisect,sys
v0=1290.0
def load(f,shift):
    r=[x for x in csv.reader(open(f)) if len(x)==5][1:]
    t=[float(x[0])-shift/v0*1e3 for x in r]   # shift in um -> ns: um/(m/s)=1e-6/1 s = 1e3 ns
    return t,[float(x[1])-shift for x in r],[float(x[2]) for x in r]
def at(d,t,k):
    i=bisect.bisect(d[0],t)
    if i<=0 or i>=len(d[0]): return float('nan')
    t0,t1=d[0][i-1],d[0][i]; return d[k][i-1]+(d[k][i]-d[k][i-1])*(t-t0)/(t1-t0)
for arg in sys.argv[1:]:
    f,N,rad=arg.split(':'); dx=7.38/float(N); sh=float(rad)*dx
    d=load('h_'+f+'.csv',sh)
    i=max(range(len(d[1])),key=lambda k:d[1][k])
    print("%-16s Pmax %6.2f at %5.1f ns | V(5,10,25 ns) %4.0f %4.0f %4.0f | P(25,50,100,200) %s"%(f,d[1][i],d[0][i],at(d,5,2),at(d,10,2),at(d,25,2)," ".join("%6.2f"%at(d,t,1) for t in [25,50,100,200])))
