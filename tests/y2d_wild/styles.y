/* Comment and layout styles of public deck generators: a Qt exporter's padded banner, Y's
   own indented section titles, comments after values, a comment over several lines, a time
   table in code 231 with blank lines between sets. Twin: styles_plain.y. */
/* *************************************ACKNOWLEDGEMENT************************************** */
/* This Input File Was Automatically Generated With A Pre-processor                           */
/* *******************************2026/11/24(Tuesday) 12:00:00******************************* */

     /*   Control     */
/YD/YDC/MCSTEP 400	/* maximum number of time steps */ 
/YD/YDC/NCSTEP 0
/YD/YDC/DCGRAY -9.81
/YD/YDC/DCSTEC 5e-07
/YD/YDC/DCTIME 0.0
/YD/YDC/ICOUTF 100
/YD/YDC/ICOUTI 0
/YD/YDC/ICOUTP 4
     /*   Elements     */
/YD/YDE/MELEM 100
/YD/YDE/NELEM 16
/YD/YDE/MELST 1
/YD/YDE/NELST 1
/YD/YDE/MELNO 4
/YD/YDE/NELNO 3
/YD/YDE/I1ELPR 16
0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0
/YD/YDE/I2ELTO 21 3 16
0 1 6
0 6 5
1 2 7
1 7 6
2 3 8
2 8 7
3 4 9
3 9 8
5 6 11
5 11 10
6 7 12
6 12 11
7 8 13
7 13 12
8 9 14
8 14 13
/YD/YDI/MICOUP 2000
/YD/YDI/NICOUP 0
/YD/YDI/IIECFF -2
/YD/YDI/DIEDI 200.0
/YD/YDI/DIEZON 4.000000e-03
/YD/YDI/MISTATE 6
/*  Nodes  */ 
/YD/YDN/MNODIM 2
/YD/YDN/NNODIM 2
/YD/YDN/MNOPO 660
/YD/YDN/NNOPO 15
/YD/YDN/D2NCC 21 2 15
0.0 0.0
0.05 0.0
0.1 0.0
0.15 0.0
0.2 0.0
0.0 0.05
0.05 0.05
0.1 0.05
0.15 0.05
0.2 0.05
0.0 0.1
0.05 0.1
0.1 0.1
0.15 0.1
0.2 0.1
/YD/YDN/D2NCI 21 2 15
0.0 0.0
0.05 0.0
0.1 0.0
0.15 0.0
0.2 0.0
0.0 0.05
0.05 0.05
0.1 0.05
0.15 0.05
0.2 0.05
0.0 0.1
0.05 0.1
0.1 0.1
0.15 0.1
0.2 0.1
/YD/YDN/D2NVC 21 2 15
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
0.0 0.0
/YD/YDN/I1NOBF 15
1 1 1 1 1 1 1 1 1 1 1 1 1 1 1
/YD/YDN/I1NOPR 15
1 1 1 1 1 0 0 0 0 0 2 2 2 2 2
/* properties - elements */
/YD/YDPE/MPROP 1
/YD/YDPE/NPROP 1
/YD/YDPE/I1PTYP 1
1
/YD/YDPE/D1PERO 1
2400.0
/YD/YDPE/D1PELA 1
8333333333.333
/YD/YDPE/D1PEMU 1
12500000000.0
/YD/YDPE/D1PEKS 1
20000.0
/YD/YDPE/D1PEPE 1
300000000000.0
/YD/YDPE/D1PEPT 1
30000000000.0
/YD/YDPE/D1PEFR 1
0.5
/YD/YDPE/D1PSEM 1
0.0
/* Nodal properties */
/* [ DEFLT ; spc ; boundary ] */ 
/YD/YDPN/MPNSET        3 /* Maximum number of Nodal Property sets */ 
/YD/YDPN/NPNSET        3 /* Actual number of Nodal Property sets */
/YD/YDPN/MPNFACT 3 /* The number of points of time  */
/YD/YDPN/NPNFACT 3 /* D3PNFAC[2][MPNSET][MPNFACT]  */
/* Array containing for each property series of MFACT times and amplitude factors. Values of D1PNAX,
D1PNAY, D1PNAZ, D1PNAP and D1PNAT are multiplied by amplitude factors at specified times for each property 
*/
/YD/YDPN/D3PNFAC 231       2       3 3
0	1
5e-05	1
1	1


0	1
5e-05	1
1	1


0	0
5e-05	1
1	1


/YD/YDPN/I1PNFX  3
1 3 1 
/YD/YDPN/I1PNFY  3
1 3 1 
/YD/YDPN/D1PNAX  3
0 0 0 
/YD/YDPN/D1PNAY  3
0 0 -500 
$YDOIT
$YSTOP
