/* matlab_code0.y without its meshing block (what code 0 means) */
/YD/YDC/MCSTEP 	300	/* maximum number of time steps */ 
/YD/YDC/NCSTEP 	0	 	/* actual number of time steps */ 
/YD/YDC/DCSTEC 	1e-06 	/* size of time step */ 
/YD/YDC/DCTIME	0.0		/* current time. i.e. time at start of this run */
/YD/YDC/ICOUTF 	500		/* output frequency */ 
/YD/YDC/DCGRAY  -9.81		/* y gravity acceleration */		
/YD/YDC/DCSIZC  80		/* Maximum size of coordinate in any direction */
/YD/YDC/DCSIZF  0.5e+08		/* Maximum size of force in any direction */
/YD/YDC/DCSIZS 	1000e+06
/YD/YDC/DCSIZV 	20.0		/* Maximum size of velocity in any direction */
/YD/YDC/ICOUTI 	0		/* Serial number of first output associated with this run */
/YD/YDC/ICOUTP 	4 		/* Number of characters for each number in output file */ 
/*  Nodes  */ 
/YD/YDN/MNODIM        2 
/YD/YDN/NNODIM        2 /* Degrees of freedom */
/YD/YDN/MNOPO    2000  /* Maximum number of nodes  */
/YD/YDN/NNOPO 15 /*  Actual number of nodes  */ 
/YD/YDN/D2NCC        21 2 15
0 0
0.05 0
0.1 0
0.15 0
0.2 0
0 0.05
0.05 0.05
0.1 0.05
0.15 0.05
0.2 0.05
0 0.1
0.05 0.1
0.1 0.1
0.15 0.1
0.2 0.1
/YD/YDN/D2NCI        21 2 15
0 0
0.05 0
0.1 0
0.15 0
0.2 0
0 0.05
0.05 0.05
0.1 0.05
0.15 0.05
0.2 0.05
0 0.1
0.05 0.1
0.1 0.1
0.15 0.1
0.2 0.1
/YD/YDN/D2NVC        21 2 15
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
0 0
/YD/YDN/I1NOBF  15
1   1   1   1   1   1   1   1   1   1   1   1   1   1   1   
/YD/YDN/I1NOPR  15
1   1   1   1   1   0   0   0   0   0   2   2   2   2   2   
/YD/YDN/D1NMCT 0
/* Nodal properties */
/*  Node Properties  */ 
/* [ DEFLT ; spc ; boundary ] */ 
/YD/YDPN/MPNSET        3 /* Maximum number of Nodal Property sets */ 
/YD/YDPN/NPNSET        3 /* Actual number of Nodal Property sets */
/YD/YDPN/I1PNFX  3
1 3 1 
/YD/YDPN/I1PNFY  3
1 3 1 
/YD/YDPN/D1PNAX  3
0 0 0 
/YD/YDPN/D1PNAY  3
0 0 -1000 
/YD/YDPN/D1PNAP  3
0 0 0 
/YD/YDPN/D1PNAT  3
0 0 0 
/* Elements */
/YD/YDE/MELEM 1000
/YD/YDE/NELEM 16
/YD/YDE/MELST         2 
/YD/YDE/NELST         2 
/YD/YDE/MELNO         4 
/YD/YDE/NELNO         3 
/YD/YDE/I1ELBE 16
0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0  

/YD/YDE/I1ELPR 16
0  0  0  0  1  1  1  1  0  0  0  0  1  1  1  1  

/YD/YDE/I2ELTO        21       3 16
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
/YD/YDE/D2ELST        21 2 0
/* interaction */
/YD/YDI/MICOUP  1000	  	/* Maximum number of contacting couples of finite elements */
/YD/YDI/NICOUP 	0		/* Actual number of contacting couples of finite elements (always set to zero) */ 
/YD/YDI/DIEZON  0.005 		/* Size of the buffer around each finite element for contact detection purposes */
/YD/YDI/IIECFF  -2		/* Internal variable used for contact (always set to -2) */
/YD/YDI/DIEDI   200.0
/YD/YDI/D1IESL  0
/YD/YDI/I1IECN  0 
/YD/YDI/I1IECT  0 
/YD/YDI/MISTATE 6
/* output database */ 
/YD/YDO/MOHYS 1 
/YD/YDO/NOHYS 1
/YD/YDO/DOHYP 0.0005
/YD/YDO/D1OHYC 1
1.0
/YD/YDO/D1OHYF 1
1.0 
/YD/YDO/D1OHYS 1
0
/YD/YDO/D1OHYT 1 
0 
/YD/YDO/D1OHYX 1 
0 
/YD/YDO/D1OHYY 1 
0 
/YD/YDO/I1OHYT 1 
15
/* properties - elements */
/YD/YDPE/MPROP 		2  /* Maximum number of properties sets */ 
/YD/YDPE/NPROP 		2  /* Actual number of properties sets */
/YD/YDPE/D1PEKS   	2
1.2e+06	1.2e+06	
/* array containing Lamé elastic constant (lamda) */
/YD/YDPE/D1PELA   	2
5.96273e+09	5.96273e+09	
/YD/YDPE/D1PEMU   	2
1.3913e+10	1.3913e+10	
/YD/YDPE/D1PERO   	2
2500	2500	
/YD/YDPE/D1PEPE   	2
2.98137e+11	2.98137e+11	
/YD/YDPE/D1PEPT   	2
2.98137e+10	2.98137e+10	
/YD/YDPE/D1PSEM   	2
0	0	
/YD/YDPE/I1PEFR   	2
0	0	
/* array containing fracture flag */
/YD/YDPE/I1PEMB   	2
0	0	
/* If greater than zero boundary nodes are marked, otherwise not */
/YD/YDPE/I1PSDE   	2
0	0	
/YD/YDPE/I1PTYP   	2
1	1	
/* array containing the type of each property */
/YD/YDPE/D1PEFR   	2
0.7	0.7	
/* array containing coloumb friction */
/* properties - joints */
/YD/YDPJ/MPJSET 2		/* Maximum number of Joint sets */
/YD/YDPJ/NPJSET 2		/* Actual number of Joint sets */
/YD/YDPJ/D1PJFS 2		
5.95e9  7.8e8	/* array containing shear strength */
/YD/YDPJ/D1PJFT	2
11.5e8   2.1e8		/* array containing tensile strength */ 
/YD/YDPJ/D1PJCO	2
2e9	2e8
/YD/YDPJ/D1PJFR	2
0.7	0.7
/YD/YDPJ/D1PJPE 2
1.41e+13   1.41e+13	/* array containing fracture penalty term for contact */
/YD/YDPJ/D1PJGF	2
8.5   6		/* array containing fracture energy Gf of material */
/YD/YDPJ/I1PSDE 2
0          0			/* array containing ID of elastic damage state variable */
/YD/YDPJ/I1PTYP 2
3          3
$YDOIT
$YSTOP
