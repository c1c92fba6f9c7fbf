set title 'Speed-up over the tree-walking interpreter (Figure 3 of Girgin and Preux)'
set xlabel 'depth of the complete tree'
set ylabel 'speed-up'
set key top left
set grid
set logscale y
set terminal pngcairo size 900,600
set output 'jit.png'
plot 'jit.dat' index 0 using 1:2 with linespoints pt 7 lw 2 lc 1 title 'jit {+,-,*,/}', 'jit.dat' index 1 using 1:2 with linespoints pt 7 lw 2 lc 2 title 'aot {+,-,*,/}', 'jit.dat' index 2 using 1:2 with linespoints pt 7 lw 2 lc 3 title 'batch {+,-,*,/}', 'jit.dat' index 3 using 1:2 with linespoints pt 7 lw 2 lc 4 title 'interp {+,-,*,/}', 'jit.dat' index 4 using 1:2 with linespoints pt 7 lw 2 lc 1 dt 2 title 'jit +sin,cos,sqrt', 'jit.dat' index 5 using 1:2 with linespoints pt 7 lw 2 lc 2 dt 2 title 'aot +sin,cos,sqrt', 'jit.dat' index 6 using 1:2 with linespoints pt 7 lw 2 lc 3 dt 2 title 'batch +sin,cos,sqrt', 'jit.dat' index 7 using 1:2 with linespoints pt 7 lw 2 lc 4 dt 2 title 'interp +sin,cos,sqrt', 'jit.dat' index 8 using 1:2 with linespoints pt 7 lw 2 lc 7 title 'paper, GNU Lightning (about 75x at depth 8)'
set terminal svg size 900,600
set output 'jit.svg'
plot 'jit.dat' index 0 using 1:2 with linespoints pt 7 lw 2 lc 1 title 'jit {+,-,*,/}', 'jit.dat' index 1 using 1:2 with linespoints pt 7 lw 2 lc 2 title 'aot {+,-,*,/}', 'jit.dat' index 2 using 1:2 with linespoints pt 7 lw 2 lc 3 title 'batch {+,-,*,/}', 'jit.dat' index 3 using 1:2 with linespoints pt 7 lw 2 lc 4 title 'interp {+,-,*,/}', 'jit.dat' index 4 using 1:2 with linespoints pt 7 lw 2 lc 1 dt 2 title 'jit +sin,cos,sqrt', 'jit.dat' index 5 using 1:2 with linespoints pt 7 lw 2 lc 2 dt 2 title 'aot +sin,cos,sqrt', 'jit.dat' index 6 using 1:2 with linespoints pt 7 lw 2 lc 3 dt 2 title 'batch +sin,cos,sqrt', 'jit.dat' index 7 using 1:2 with linespoints pt 7 lw 2 lc 4 dt 2 title 'interp +sin,cos,sqrt', 'jit.dat' index 8 using 1:2 with linespoints pt 7 lw 2 lc 7 title 'paper, GNU Lightning (about 75x at depth 8)'
