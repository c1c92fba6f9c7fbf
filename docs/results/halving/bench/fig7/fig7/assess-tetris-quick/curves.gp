set title 'tetris (tetris-quick)'
set xlabel 'lambda-PI iteration'
set ylabel 'mean return'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'curves.png'
plot 'curves.dat' index 0 using 1:3:4 with filledcurves lc 1 fs transparent solid 0.2 notitle, 'curves.dat' index 1 using 1:3:4 with filledcurves lc 2 fs transparent solid 0.2 notitle, 'curves.dat' index 2 using 1:3:4 with filledcurves lc 3 fs transparent solid 0.2 notitle, 'curves.dat' index 3 using 1:3:4 with filledcurves lc 4 fs transparent solid 0.2 notitle, 'curves.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'original', 'curves.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-03', 'curves.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-07', 'curves.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'no-learning'
set terminal svg size 900,600
set output 'curves.svg'
plot 'curves.dat' index 0 using 1:3:4 with filledcurves lc 1 fs transparent solid 0.2 notitle, 'curves.dat' index 1 using 1:3:4 with filledcurves lc 2 fs transparent solid 0.2 notitle, 'curves.dat' index 2 using 1:3:4 with filledcurves lc 3 fs transparent solid 0.2 notitle, 'curves.dat' index 3 using 1:3:4 with filledcurves lc 4 fs transparent solid 0.2 notitle, 'curves.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'original', 'curves.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-03', 'curves.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-07', 'curves.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'no-learning'
